# Stability at the extremes (issue 6): the parameter matrix and run-time guards.
