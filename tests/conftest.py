import strand  # noqa: F401  (the dolfinx wheel's libraries load before petsc4py/dolfinx)
