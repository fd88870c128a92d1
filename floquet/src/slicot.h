// The SLICOT 5.0 routines ltp calls (Fortran 77, gfortran ABI): every argument by pointer, the
// lengths of CHARACTER arguments appended as hidden size_t arguments. Argument lists checked
// against the SLICOT 5.0 sources of MB03VD.f, MB03VY.f and MB03BD.f.
#pragma once

#include <cstddef>

extern "C" {
/// Periodic Hessenberg-triangular reduction of A_1 A_2 ⋯ A_p (reflectors left below the band).
void mb03vd_(const int* n, const int* p, const int* ilo, const int* ihi, double* a, const int* lda1,
             const int* lda2, double* tau, const int* ldtau, double* dwork, int* info);
/// The orthogonal Q_j of MB03VD from its reflectors (overwrites a).
void mb03vy_(const int* n, const int* p, const int* ilo, const int* ihi, double* a, const int* lda1,
             const int* lda2, const double* tau, const int* ldtau, double* dwork, const int* ldwork,
             int* info);
/// Periodic QZ: eigenvalues, optionally the periodic Schur form and its Schur vectors.
void mb03bd_(const char* job, const char* defl, const char* compq, const int* qind, const int* k,
             const int* n, const int* h, const int* ilo, const int* ihi, const int* s, double* a,
             const int* lda1, const int* lda2, double* q, const int* ldq1, const int* ldq2,
             double* alphar, double* alphai, double* beta, int* scal, int* iwork, const int* liwork,
             double* dwork, const int* ldwork, int* iwarn, int* info, std::size_t job_len,
             std::size_t defl_len, std::size_t compq_len);
}
