#include <GLFW/glfw3.h>
#include "window/keys.h"
