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
            character, intent(in) :: uplo
            integer, intent(in) :: n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: info
        end subroutine dpotrf
        !> Reciprocal 1-norm condition estimate from a Cholesky factor.
        pure subroutine dpocon(uplo, n, a, lda, anorm, rcond, work, iwork, info)
            import :: wp
            character, intent(in) :: uplo
            integer, intent(in) :: n, lda
            real(wp), intent(in) :: a(lda, *), anorm
            real(wp), intent(out) :: rcond, work(*)
            integer, intent(out) :: iwork(*), info
        end subroutine dpocon
        !> Norm of a symmetric matrix.
        function dlansy(norm, uplo, n, a, lda, work) result(r)
            import :: wp
            character, intent(in) :: norm, uplo
            integer, intent(in) :: n, lda
            real(wp), intent(in) :: a(lda, *)
            real(wp), intent(inout) :: work(*)
            real(wp) :: r
        end function dlansy
        !> LU factorization with partial pivoting.
        pure subroutine dgetrf(m, n, a, lda, ipiv, info)
            import :: wp
            integer, intent(in) :: m, n, lda
            real(wp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*), info
        end subroutine dgetrf
        !> Solve with an LU factorization from dgetrf.
        pure subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: wp
            character, intent(in) :: trans
            integer, intent(in) :: n, nrhs, lda, ldb
            real(wp), intent(in) :: a(lda, *)
            integer, intent(in) :: ipiv(*)
            real(wp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
        end subroutine dgetrs
        !> Eigenvalues and, optionally, left and right eigenvectors of a
        !! general real matrix (lwork = -1: workspace query into work(1)).
        pure subroutine dgeev(jobvl, jobvr, n, a, lda, wr, wi, vl, ldvl, vr, ldvr, work, lwork, info)
            import :: wp
            character, intent(in) :: jobvl, jobvr
            integer, intent(in) :: n, lda, ldvl, ldvr, lwork
            real(wp), intent(inout) :: a(lda, *)
            real(wp), intent(out) :: wr(*), wi(*), vl(ldvl, *), vr(ldvr, *), work(*)
            integer, intent(out) :: info
        end subroutine dgeev
    end interface
end module hn_lapack
