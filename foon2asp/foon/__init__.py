"""Reading FOONs, kitchens and tree files into the model, and the problem of integer ids the solvers share."""
