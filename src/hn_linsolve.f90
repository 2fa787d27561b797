!> Solution of a_ij xddot_j = f_i: Gaussian elimination with partial
!! pivoting (the paper's method, own code) or LAPACK Cholesky (dposv),
!! and a condition estimate of a_ij.
module hn_linsolve
    use hn_kinds, only: wp, zero, one, msglen
    use hn_lapack, only: dposv, dpotrf, dpocon, dlansy
    implicit none
    private

    public :: solver_gauss, solver_cholesky, solver_name, gauss_solve, cholesky_solve
    public :: linear_solve, spd_rcond

    integer, parameter :: solver_gauss = 1     !! Gaussian elimination, partial pivoting
    integer, parameter :: solver_cholesky = 2  !! LAPACK dposv

contains

    !> Name of a solver code.
    pure function solver_name(code) result(s)
        integer, intent(in) :: code
        character(len=:), allocatable :: s
        select case (code)
        case (solver_gauss); s = 'GAUSS'
        case (solver_cholesky); s = 'CHOLESKY'
        case default; s = 'UNKNOWN'
        end select
    end function solver_name

    !> Solve a x = b by Gaussian elimination with partial pivoting.
    !! `a` and `b` are overwritten (b holds x on return). stat /= 0 when a
    !! pivot is zero or below n*eps times the largest entry (singular).
    pure subroutine gauss_solve(a, b, stat)
        real(wp), intent(inout) :: a(:, :)
        real(wp), intent(inout) :: b(:)
        integer, intent(out) :: stat
        integer :: n, j, k, piv
        real(wp) :: tb, tol, tmp
        n = size(b)
        stat = 0
        tol = real(n, wp)*epsilon(one)*maxval(abs(a(1:n, 1:n)))
        do k = 1, n
            piv = k - 1 + maxloc(abs(a(k:n, k)), dim=1)
            if (.not. (abs(a(piv, k)) > tol)) then
                stat = k
                return
            end if
            if (piv /= k) then
                do j = k, n
                    tmp = a(k, j); a(k, j) = a(piv, j); a(piv, j) = tmp
                end do
                tb = b(k); b(k) = b(piv); b(piv) = tb
            end if
            ! multipliers in column k, then column-by-column updates (unit stride)
            a(k + 1:n, k) = a(k + 1:n, k)/a(k, k)
            do j = k + 1, n
                if (a(k, j) /= zero) a(k + 1:n, j) = a(k + 1:n, j) - a(k + 1:n, k)*a(k, j)
            end do
            b(k + 1:n) = b(k + 1:n) - a(k + 1:n, k)*b(k)
        end do
        ! back substitution, column oriented
        do k = n, 1, -1
            b(k) = b(k)/a(k, k)
            b(1:k - 1) = b(1:k - 1) - a(1:k - 1, k)*b(k)
        end do
    end subroutine gauss_solve

    !> Solve a x = b for symmetric positive definite a with LAPACK dposv.
    !! stat /= 0 when a is not positive definite.
    pure subroutine cholesky_solve(a, b, stat)
        real(wp), intent(inout) :: a(:, :)
        real(wp), intent(inout) :: b(:)
        integer, intent(out) :: stat
        integer :: n
        n = size(b)
        call dposv('U', n, 1, a, size(a, 1), b, n, stat)
    end subroutine cholesky_solve

    !> Solve with the selected method; on failure errmsg says why.
    pure subroutine linear_solve(method, a, b, stat, errmsg)
        integer, intent(in) :: method
        real(wp), intent(inout) :: a(:, :), b(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        errmsg = ''
        select case (method)
        case (solver_cholesky)
            call cholesky_solve(a, b, stat)
            if (stat /= 0) write (errmsg, '(a,i0)') &
                'a_ij is not positive definite (Cholesky failed at row ', stat
        case default
            call gauss_solve(a, b, stat)
            if (stat /= 0) write (errmsg, '(a,i0)') &
                'a_ij is singular to working precision (zero pivot at row ', stat
        end select
        if (stat /= 0) errmsg = trim(errmsg)//')'
    end subroutine linear_solve

    !> Reciprocal 1-norm condition number estimate of a symmetric positive
    !! definite matrix (LAPACK dpotrf + dpocon); 0 when not positive definite.
    subroutine spd_rcond(a, rcond)
        real(wp), intent(in) :: a(:, :)
        real(wp), intent(out) :: rcond
        real(wp) :: f(size(a, 1), size(a, 2)), work(3*size(a, 1)), anorm
        integer :: iwork(size(a, 1)), info, n
        n = size(a, 1)
        f = a
        anorm = dlansy('1', 'U', n, f, n, work)
        call dpotrf('U', n, f, n, info)
        if (info /= 0) then
            rcond = zero
            return
        end if
        call dpocon('U', n, f, n, anorm, rcond, work, iwork, info)
    end subroutine spd_rcond

end module hn_linsolve
