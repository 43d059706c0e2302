#include "solve/linear_start.h"
