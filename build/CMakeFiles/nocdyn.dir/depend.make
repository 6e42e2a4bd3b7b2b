# Empty dependencies file for nocdyn.
# This may be replaced when dependencies are built.
