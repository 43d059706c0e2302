#include "daylight/local_time.h"
