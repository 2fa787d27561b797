!> Explicit interfaces to the LAPACK routines the project calls.
module hn_lapack
    use hn_kinds, only: wp
    implicit none
    private

    public :: dpotrf, dpocon, dlansy, dgetrf, dgetrs, dgeev

    interface
        !> Cholesky factorization of a symmetric positive definite matrix.
        pure subroutine dpotrf(uplo, n, a, lda, info)
            import :: wp
            character, intent(in) :: uplo          !! 'U': factor the upper triangle of a; 'L': the lower
            integer, intent(in) :: n               !! order of a
            integer, intent(in) :: lda             !! leading dimension of a (>= max(1, n))
            real(wp), intent(inout) :: a(lda, *)   !! in: symmetric matrix; out: factor U (a = U^T U) or L (L L^T)
            integer, intent(out) :: info           !! 0: ok; < 0: argument -info illegal; > 0: minor info not SPD
        end subroutine dpotrf
        !> Reciprocal 1-norm condition estimate from a Cholesky factor.
        pure subroutine dpocon(uplo, n, a, lda, anorm, rcond, work, iwork, info)
            import :: wp
            character, intent(in) :: uplo       !! 'U' or 'L': which factor a holds (as passed to dpotrf)
            integer, intent(in) :: n            !! order of a
            integer, intent(in) :: lda          !! leading dimension of a (>= max(1, n))
            real(wp), intent(in) :: a(lda, *)   !! the Cholesky factor from dpotrf
            real(wp), intent(in) :: anorm       !! 1-norm of the original matrix (dlansy '1')
            real(wp), intent(out) :: rcond      !! reciprocal of the estimated 1-norm condition number
            real(wp), intent(out) :: work(*)    !! workspace (3 n)
            integer, intent(out) :: iwork(*)    !! workspace (n)
            integer, intent(out) :: info        !! 0: ok; < 0: argument -info illegal
        end subroutine dpocon
        !> Norm of a symmetric matrix.
        function dlansy(norm, uplo, n, a, lda, work) result(r)
            import :: wp
            character, intent(in) :: norm        !! 'M' max |a_ij|, '1'/'O' 1-norm, 'I' infinity-norm, 'F'/'E' Frobenius
            character, intent(in) :: uplo        !! 'U' or 'L': which triangle of a is referenced
            integer, intent(in) :: n             !! order of a (0: the norm is 0)
            integer, intent(in) :: lda           !! leading dimension of a (>= max(1, n))
            real(wp), intent(in) :: a(lda, *)    !! the symmetric matrix (one triangle referenced)
            real(wp), intent(inout) :: work(*)   !! workspace (n for '1', 'O' or 'I'; else not referenced)
            real(wp) :: r
        end function dlansy
        !> LU factorization with partial pivoting.
        pure subroutine dgetrf(m, n, a, lda, ipiv, info)
            import :: wp
            integer, intent(in) :: m               !! number of rows of a
            integer, intent(in) :: n               !! number of columns of a
            integer, intent(in) :: lda             !! leading dimension of a (>= max(1, m))
            real(wp), intent(inout) :: a(lda, *)   !! in: the m x n matrix; out: L (unit diagonal not stored) and U
            integer, intent(out) :: ipiv(*)        !! (min(m, n)) pivot indices: row i was interchanged with row ipiv(i)
            integer, intent(out) :: info           !! 0: ok; < 0: argument -info illegal; > 0: u(info, info) = 0
        end subroutine dgetrf
        !> Solve with an LU factorization from dgetrf.
        pure subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: wp
            character, intent(in) :: trans         !! 'N': solve a x = b; 'T' or 'C': a^T x = b
            integer, intent(in) :: n               !! order of a
            integer, intent(in) :: nrhs            !! number of right-hand sides (columns of b)
            integer, intent(in) :: lda             !! leading dimension of a (>= max(1, n))
            integer, intent(in) :: ldb             !! leading dimension of b (>= max(1, n))
            real(wp), intent(in) :: a(lda, *)      !! the factors L and U from dgetrf
            integer, intent(in) :: ipiv(*)         !! (n) the pivot indices from dgetrf
            real(wp), intent(inout) :: b(ldb, *)   !! in: the right-hand sides; out: the solutions x
            integer, intent(out) :: info           !! 0: ok; < 0: argument -info illegal
        end subroutine dgetrs
        !> Eigenvalues and, optionally, left and right eigenvectors of a
        !! general real matrix (lwork = -1: workspace query into work(1)).
        pure subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
            import :: wp
            character, intent(in) :: jobvl         !! 'N': left eigenvectors not computed; 'V': computed
            character, intent(in) :: jobvr         !! 'N': right eigenvectors not computed; 'V': computed
            integer, intent(in) :: n               !! order of a
            integer, intent(in) :: lda             !! leading dimension of a (>= max(1, n))
            integer, intent(in) :: ldvl            !! leading dimension of vl (>= 1; >= n when jobvl = 'V')
            integer, intent(in) :: ldvr            !! leading dimension of vr (>= 1; >= n when jobvr = 'V')
            integer, intent(in) :: lwork           !! size of work; -1: workspace query
            real(wp), intent(inout) :: a(lda, *)   !! in: the matrix; out: overwritten
            real(wp), intent(out) :: wr(*)         !! (n) real parts of the eigenvalues
            real(wp), intent(out) :: wi(*)         !! (n) imaginary parts (a complex pair: positive first)
            real(wp), intent(out) :: vl(ldvl, *)   !! (n) left eigenvectors (jobvl = 'V')
            real(wp), intent(out) :: vr(ldvr, *)   !! (n) right eigenvectors (jobvr = 'V'; a pair: columns j, j+1 = re, im)
            real(wp), intent(out) :: work(*)       !! (lwork) workspace; work(1): the optimal lwork
            integer, intent(out) :: info           !! 0: ok; < 0: argument -info illegal; > 0: QR failed
        end subroutine dgeev
    end interface
end module hn_lapack
