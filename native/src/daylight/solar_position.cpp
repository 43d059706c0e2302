#include "daylight/solar_position.h"
