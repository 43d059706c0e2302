#include "daylight/sky_models.h"
