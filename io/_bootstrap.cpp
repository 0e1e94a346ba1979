#include "io/little_endian.hpp"
