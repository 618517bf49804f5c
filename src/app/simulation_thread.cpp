// Placeholder: the simulation thread is being written.
#include "simulation_thread.h"
