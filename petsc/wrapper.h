/* What bindgen sees of the system PETSc and METIS (feature `petsc`). */
#include <petscksp.h>
#include <petscmat.h>
#include <metis.h>
