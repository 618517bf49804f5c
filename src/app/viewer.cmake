# Placeholder: the window target is being written.
