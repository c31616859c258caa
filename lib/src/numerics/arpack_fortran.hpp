/// @file
/// @brief Internal: prototypes of ARPACK's Fortran 77 drivers — symmetric dsaupd/dseupd and
/// non-symmetric dnaupd/dneupd — as built by gfortran (Debian libarpack2 3.8, 32-bit integers),
/// and the process-wide mutex every ARPACK call holds. Private to geardyn_core (architecture
/// §3.1, §3.11): no public header includes this.
///
/// Fortran conventions: every argument by reference; LOGICAL is a 4-byte integer (0 = .FALSE.);
/// each CHARACTER argument adds a hidden trailing length argument of type size_t (gfortran ≥ 8),
/// in the order of the character arguments. Reference: ARPACK Users' Guide (Lehoucq, Sorensen,
/// Yang, SIAM 1998) and the argument lists in arpack-ng's SRC/dsaupd.f, SRC/dseupd.f, SRC/dnaupd.f
/// and SRC/dneupd.f.
#pragma once

#include <cstddef>
#include <mutex>

extern "C" {

/// Reverse-communication implicitly restarted Lanczos (ARPACK dsaupd).
void dsaupd_(int* ido, const char* bmat, const int* n, const char* which, const int* nev,
             const double* tol, double* resid, const int* ncv, double* v, const int* ldv,
             int* iparam, int* ipntr, double* workd, double* workl, const int* lworkl, int* info,
             std::size_t bmat_len, std::size_t which_len);

/// Ritz values and vectors after dsaupd (ARPACK dseupd).
void dseupd_(const int* rvec, const char* howmny, int* select, double* d, double* z, const int* ldz,
             const double* sigma, const char* bmat, const int* n, const char* which, const int* nev,
             const double* tol, double* resid, const int* ncv, double* v, const int* ldv,
             int* iparam, int* ipntr, double* workd, double* workl, const int* lworkl, int* info,
             std::size_t howmny_len, std::size_t bmat_len, std::size_t which_len);

/// Reverse-communication implicitly restarted Arnoldi (ARPACK dnaupd).
void dnaupd_(int* ido, const char* bmat, const int* n, const char* which, const int* nev,
             const double* tol, double* resid, const int* ncv, double* v, const int* ldv,
             int* iparam, int* ipntr, double* workd, double* workl, const int* lworkl, int* info,
             std::size_t bmat_len, std::size_t which_len);

/// Ritz values and vectors after dnaupd (ARPACK dneupd).
void dneupd_(const int* rvec, const char* howmny, int* select, double* dr, double* di, double* z,
             const int* ldz, const double* sigmar, const double* sigmai, double* workev,
             const char* bmat, const int* n, const char* which, const int* nev, const double* tol,
             double* resid, const int* ncv, double* v, const int* ldv, int* iparam, int* ipntr,
             double* workd, double* workl, const int* lworkl, int* info, std::size_t howmny_len,
             std::size_t bmat_len, std::size_t which_len);

}  // extern "C"

namespace geardyn::internal {

/// ARPACK keeps the reverse-communication state in Fortran SAVE variables: every driver call
/// (symmetric or not) holds this one mutex.
std::mutex& ArpackMutex();

}  // namespace geardyn::internal
