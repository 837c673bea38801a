#include "sculpt/hal/parsers/parser.h"
