# (empty so far)
