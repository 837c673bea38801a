#pragma once
// OpenGL 3.3 core entry points. Linux's libGL (GLVND) exports every core
// function, so prototypes suffice and no loader library is needed; GLFW is
// told not to include a GL header of its own.
#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
