#include "solve/genetic.h"
