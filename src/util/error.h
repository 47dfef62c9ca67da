#pragma once

// Error is part of the public API (include/streak/error.h): the one type every layer throws
// for bad input. Only the command line turns it into stderr output and exit code 2; library
// code never exits.
#include "streak/error.h"
