#include "solve/nnls.h"
