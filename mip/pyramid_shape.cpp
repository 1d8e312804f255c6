// pyramid_shape.h is header-only; this unit keeps the library non-empty until the pyramids land.
#include "mip/pyramid_shape.h"
