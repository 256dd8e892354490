/* liboit umbrella header. */
#ifndef OIT_OIT_H
#define OIT_OIT_H
#include "status.h"
#include "mesh.h"
#include "liboit.h"
#include "offscreen.h"
#endif
