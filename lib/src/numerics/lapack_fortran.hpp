/// @file
/// @brief Internal: the prototype of LAPACK's dstemr (eigenpairs of a symmetric tridiagonal
/// matrix by multiple relatively robust representations), as built by gfortran (Debian
/// liblapack3, 32-bit integers). Private to geardyn_core (architecture §3.1, §3.11).
///
/// Fortran conventions: every argument by reference; LOGICAL is a 4-byte integer (0 = .FALSE.);
/// each CHARACTER argument adds a hidden trailing length argument of type size_t (gfortran ≥ 8),
/// in the order of the character arguments. Reference: the argument list in LAPACK 3.x
/// SRC/dstemr.f.
#pragma once

#include <cstddef>

extern "C" {

/// Selected eigenvalues and eigenvectors of a real symmetric tridiagonal matrix (LAPACK dstemr).
void dstemr_(const char* jobz, const char* range, const int* n, double* d, double* e,
             const double* vl, const double* vu, const int* il, const int* iu, int* m, double* w,
             double* z, const int* ldz, const int* nzc, int* isuppz, int* tryrac, double* work,
             const int* lwork, int* iwork, const int* liwork, int* info, std::size_t jobz_len,
             std::size_t range_len);

}  // extern "C"
