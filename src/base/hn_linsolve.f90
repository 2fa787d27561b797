!> Solution of a_ij xddot_j = f_i: Gaussian elimination with partial
!! pivoting (the paper's method, own code) or Cholesky (own code),
!! and a condition estimate of a_ij.
module hn_linsolve
    use hn_kinds, only: wp, zero, one, msglen
    use hn_status, only: stat_ok, stat_singular, stat_ill_conditioned
    use hn_lapack, only: dpotrf, dpocon, dlansy
    implicit none
    private

    public :: solver_gauss, solver_cholesky, solver_articulated, solver_name, solver_names, solver_code
    public :: gauss_solve, cholesky_solve, cholesky_factor, cholesky_substitute
    public :: linear_solve, spd_rcond

    integer, parameter :: solver_gauss = 1     !! Gaussian elimination, partial pivoting
    integer, parameter :: solver_cholesky = 2  !! Cholesky (with a_ij and f_i by the recursive forms)
    integer, parameter :: solver_articulated = 3  !! articulated-body algorithm, O(n), no a_ij
    !> Deck names of the solvers, in the order of their codes.
    character(len=8), parameter :: solver_names(3) = [character(len=8) :: 'GAUSS', 'CHOLESKY', 'ABA']

contains

    !> Name of a solver code.
    pure function solver_name(code) result(s)
        integer, intent(in) :: code   !! solver code (solver_gauss, solver_cholesky, solver_articulated)
        character(len=:), allocatable :: s
        if (code >= 1 .and. code <= size(solver_names)) then
            s = trim(solver_names(code))
        else
            s = 'UNKNOWN'
        end if
    end function solver_name

    !> Code of a solver's deck name; 0 when unknown.
    pure integer function solver_code(name) result(code)
        character(len=*), intent(in) :: name   !! deck name ('GAUSS', 'CHOLESKY', 'ABA'), upper case
        code = findloc(solver_names, name, dim=1)
    end function solver_code

    !> Solve a x = b by Gaussian elimination with partial pivoting.
    !! `a` and `b` are overwritten (b holds x on return). stat = stat_singular
    !! when a pivot is zero or below n*eps times the largest entry.
    !! pivot_ratio: smallest over largest |pivot| (a conditioning indicator).
    pure subroutine gauss_solve(a, b, stat, pivot_ratio, pivot_row)
        real(wp), intent(inout) :: a(:, :)               !! (n, n) in: the matrix; out: overwritten by its LU factors
        real(wp), intent(inout) :: b(:)                  !! (n) in: the right-hand side; out: the solution x
        integer, intent(out) :: stat                     !! stat_ok, or stat_singular (pivot at most n eps max|a|)
        real(wp), intent(out), optional :: pivot_ratio   !! smallest over largest |pivot| (0 when singular)
        integer, intent(out), optional :: pivot_row      !! row of the smallest pivot
        integer :: n, j, k, piv, kmin
        real(wp) :: tb, tol, tmp, pmin, pmax
        n = size(b)
        stat = stat_ok
        tol = real(n, wp)*epsilon(one)*maxval(abs(a(1:n, 1:n)))
        pmin = huge(one); pmax = zero; kmin = 1
        do k = 1, n
            piv = k - 1 + maxloc(abs(a(k:n, k)), dim=1)
            if (.not. (abs(a(piv, k)) > tol)) then
                stat = stat_singular
                if (present(pivot_ratio)) pivot_ratio = zero
                if (present(pivot_row)) pivot_row = k
                return
            end if
            if (abs(a(piv, k)) < pmin) then
                pmin = abs(a(piv, k)); kmin = k
            end if
            pmax = max(pmax, abs(a(piv, k)))
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
        if (present(pivot_ratio)) pivot_ratio = pmin/max(pmax, tiny(one))
        if (present(pivot_row)) pivot_row = kmin
    end subroutine gauss_solve

    !> Solve a x = b for symmetric positive definite a by Cholesky
    !! factorization a = L L^T (own column-oriented code: for the sizes of
    !! this model it is several times faster than reference LAPACK's
    !! recursive dpotrf). The lower triangle of `a` is overwritten by L, b
    !! by x. stat = stat_singular when a is not positive definite.
    pure subroutine cholesky_solve(a, b, stat, bad_row)
        real(wp), intent(inout) :: a(:, :)          !! (n, n) in: the matrix; out: L in the lower triangle
        real(wp), intent(inout) :: b(:)             !! (n) in: the right-hand side; out: the solution x
        integer, intent(out) :: stat                !! stat_ok, or stat_singular (not positive definite)
        integer, intent(out), optional :: bad_row   !! order of the leading minor that is not positive definite
        integer :: k
        call cholesky_factor(a, stat, k)
        if (present(bad_row)) bad_row = k
        if (stat /= stat_ok) return
        call cholesky_substitute(a, b)
    end subroutine cholesky_solve

    !> In-place Cholesky factor L (lower triangle) of a symmetric positive
    !! definite matrix (columns, unit stride).
    pure subroutine cholesky_factor(a, stat, bad_row)
        real(wp), intent(inout) :: a(:, :)   !! (n, n) in: the matrix; out: L in the lower triangle (upper untouched)
        integer, intent(out) :: stat         !! stat_ok, or stat_singular (not positive definite)
        integer, intent(out) :: bad_row      !! first non-positive pivot (0: none)
        call cholesky_kernel(size(a, 1), a, stat, bad_row)
    end subroutine cholesky_factor

    !> The factorization on an explicit-shape (contiguous) array, left-looking
    !! by columns: column j receives the updates of the previous columns four
    !! at a time (one pass over column j per four columns; 30 % faster than
    !! the column-by-column update at n = 48), then is scaled.
    pure subroutine cholesky_kernel(n, a, stat, bad_row)
        integer, intent(in) :: n
        real(wp), intent(inout) :: a(n, n)
        integer, intent(out) :: stat, bad_row
        integer :: i, j, k
        real(wp) :: d, b1, b2, b3, b4
        stat = stat_ok
        bad_row = 0
        do j = 1, n
            k = 1
            do while (k + 3 <= j - 1)
                b1 = a(j, k); b2 = a(j, k + 1); b3 = a(j, k + 2); b4 = a(j, k + 3)
                do i = j, n
                    a(i, j) = a(i, j) - a(i, k)*b1 - a(i, k + 1)*b2 - a(i, k + 2)*b3 - a(i, k + 3)*b4
                end do
                k = k + 4
            end do
            do while (k <= j - 1)
                b1 = a(j, k)
                do i = j, n
                    a(i, j) = a(i, j) - a(i, k)*b1
                end do
                k = k + 1
            end do
            d = a(j, j)
            if (.not. (d > zero)) then
                stat = stat_singular
                bad_row = j
                return
            end if
            d = sqrt(d)
            a(j, j) = d
            d = one/d
            do i = j + 1, n
                a(i, j) = a(i, j)*d
            end do
        end do
    end subroutine cholesky_kernel

    !> Solve L L^T x = b in place with the factor of cholesky_factor.
    pure subroutine cholesky_substitute(l, b)
        real(wp), intent(in) :: l(:, :)   !! (n, n) the factor L from cholesky_factor (lower triangle)
        real(wp), intent(inout) :: b(:)   !! (n) in: the right-hand side; out: the solution x
        call substitute_kernel(size(b), l, b)
    end subroutine cholesky_substitute

    pure subroutine substitute_kernel(n, l, b)
        integer, intent(in) :: n
        real(wp), intent(in) :: l(n, n)
        real(wp), intent(inout) :: b(n)
        integer :: i, k
        real(wp) :: s
        do k = 1, n
            b(k) = b(k)/l(k, k)
            s = b(k)
            do i = k + 1, n
                b(i) = b(i) - l(i, k)*s
            end do
        end do
        do k = n, 1, -1
            s = b(k)
            do i = k + 1, n
                s = s - l(i, k)*b(i)
            end do
            b(k) = s/l(k, k)
        end do
    end subroutine substitute_kernel

    !> Solve with the selected method; on failure errmsg says why and `row`
    !! is the unknown concerned. A pivot ratio (Gauss) or squared diagonal
    !! ratio of the factor (Cholesky) below 1e-14 counts as ill-conditioned.
    pure subroutine linear_solve(method, a, b, stat, errmsg, row)
        integer, intent(in) :: method                  !! solver_gauss or solver_cholesky (any other code: Gauss)
        real(wp), intent(inout) :: a(:, :)             !! (n, n) in: a_ij; out: overwritten by its factors
        real(wp), intent(inout) :: b(:)                !! (n) in: f_i; out: xddot_j
        integer, intent(out) :: stat                   !! stat_ok, stat_singular, or stat_ill_conditioned (x still in b)
        character(len=msglen), intent(out) :: errmsg   !! why it failed ('' when stat_ok)
        integer, intent(out) :: row                    !! the unknown of the smallest pivot, or of the failing one
        real(wp), parameter :: ill = 1.0e-14_wp
        real(wp) :: ratio, d(size(b))
        integer :: k
        errmsg = ''
        row = 0
        select case (method)
        case (solver_cholesky)
            call cholesky_solve(a, b, stat, row)
            if (stat /= stat_ok) then
                write (errmsg, '(a)') 'a_ij is not positive definite (Cholesky failed)'
                return
            end if
            d = [(abs(a(k, k)), k=1, size(b))]
            ratio = (minval(d)/max(maxval(d), tiny(one)))**2
            row = minloc(d, dim=1)
        case default
            call gauss_solve(a, b, stat, ratio, row)
            if (stat /= 0) then
                write (errmsg, '(a)') 'a_ij is singular to working precision (zero pivot)'
                return
            end if
        end select
        if (ratio < ill) then
            stat = stat_ill_conditioned
            write (errmsg, '(a,es9.2,a)') 'a_ij is ill-conditioned (pivot ratio ', ratio, ')'
        end if
    end subroutine linear_solve

    !> Reciprocal 1-norm condition number estimate of a symmetric positive
    !! definite matrix (LAPACK dpotrf + dpocon); 0 when not positive definite.
    subroutine spd_rcond(a, rcond)
        real(wp), intent(in) :: a(:, :)   !! (n, n) symmetric matrix (upper triangle used)
        real(wp), intent(out) :: rcond    !! reciprocal 1-norm condition number estimate (0: not positive definite)
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
