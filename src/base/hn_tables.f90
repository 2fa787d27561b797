!> Time tables: piecewise-linear interpolation, exact integrals of a
!! piecewise-linear table, and natural cubic splines; and two operations on
!! sampled curves: linear resampling and the central-difference derivative.
module hn_tables
    use hn_kinds, only: wp, zero, one
    use hn_status, only: stat_ok, stat_bad_table
    implicit none
    private

    public :: table_t, table_set, table_value, table_segment, spline_t, spline_set, spline_eval, resample, gradient

    !> A sampled function y(t), t strictly increasing.
    type :: table_t
        real(wp), allocatable :: t(:)  !! abscissae [s]
        real(wp), allocatable :: y(:)  !! ordinates
    end type table_t

    !> Natural cubic spline through (t, y) with second derivatives m.
    type :: spline_t
        real(wp), allocatable :: t(:), y(:), m(:)
    end type spline_t

contains

    !> Store a table; stat = stat_bad_table when it is empty, t and y differ
    !! in size, or a time does not increase (bad_point = its index).
    pure subroutine table_set(tab, t, y, stat, bad_point)
        type(table_t), intent(out) :: tab             !! the table (unallocated when stat /= stat_ok)
        real(wp), intent(in) :: t(:)                  !! abscissae, strictly increasing [s]
        real(wp), intent(in) :: y(:)                  !! ordinates at t (same size)
        integer, intent(out) :: stat                  !! stat_ok or stat_bad_table
        integer, intent(out), optional :: bad_point   !! index of the first time that does not increase (0: none)
        integer :: i
        stat = stat_ok
        if (present(bad_point)) bad_point = 0
        if (size(t) < 1 .or. size(t) /= size(y)) then
            stat = stat_bad_table; return
        end if
        do i = 2, size(t)
            if (.not. (t(i) > t(i - 1))) then
                stat = stat_bad_table
                if (present(bad_point)) bad_point = i
                return
            end if
        end do
        tab%t = t
        tab%y = y
    end subroutine table_set

    !> Segment index i with t(i) <= tt < t(i+1), clamped to [1, n-1]
    !! (0 for a one-point table). Binary search.
    pure integer function table_segment(t, tt) result(i)
        real(wp), intent(in) :: t(:)   !! abscissae, increasing
        real(wp), intent(in) :: tt     !! the abscissa to locate
        integer :: lo, hi, mid
        if (size(t) < 2) then
            i = 0; return
        end if
        lo = 1; hi = size(t)
        if (tt <= t(1)) then
            i = 1; return
        end if
        if (tt >= t(hi)) then
            i = hi - 1; return
        end if
        do while (hi - lo > 1)
            mid = (lo + hi)/2
            if (t(mid) <= tt) then
                lo = mid
            else
                hi = mid
            end if
        end do
        i = lo
    end function table_segment

    !> Linear interpolation; constant end values outside the table.
    pure real(wp) function table_value(tab, tt) result(y)
        type(table_t), intent(in) :: tab   !! the table
        real(wp), intent(in) :: tt         !! time [s]
        integer :: i
        real(wp) :: s
        i = table_segment(tab%t, tt)
        if (i == 0) then
            y = tab%y(1)
        else if (tt <= tab%t(1)) then
            y = tab%y(1)
        else if (tt >= tab%t(size(tab%t))) then
            y = tab%y(size(tab%y))
        else
            s = (tt - tab%t(i))/(tab%t(i + 1) - tab%t(i))
            y = (one - s)*tab%y(i) + s*tab%y(i + 1)
        end if
    end function table_value

    !> Natural cubic spline (zero second derivative at both ends).
    pure subroutine spline_set(sp, t, y, stat)
        type(spline_t), intent(out) :: sp   !! the spline (second derivatives m at the knots)
        real(wp), intent(in) :: t(:)        !! knots, strictly increasing [s]
        real(wp), intent(in) :: y(:)        !! values at the knots (same size)
        integer, intent(out) :: stat        !! stat_ok, or stat_bad_table (as table_set)
        integer :: n, i
        real(wp) :: h(size(t)), diag(size(t)), rhs(size(t)), w
        type(table_t) :: check
        call table_set(check, t, y, stat)
        if (stat /= 0) return
        n = size(t)
        sp%t = t; sp%y = y
        allocate (sp%m(n))
        sp%m = zero
        if (n < 3) return
        do i = 1, n - 1
            h(i) = t(i + 1) - t(i)
        end do
        ! tridiagonal system for interior second derivatives (Thomas algorithm)
        do i = 2, n - 1
            diag(i) = 2.0_wp*(h(i - 1) + h(i))
            rhs(i) = 6.0_wp*((y(i + 1) - y(i))/h(i) - (y(i) - y(i - 1))/h(i - 1))
        end do
        do i = 3, n - 1
            w = h(i - 1)/diag(i - 1)
            diag(i) = diag(i) - w*h(i - 1)
            rhs(i) = rhs(i) - w*rhs(i - 1)
        end do
        sp%m(n - 1) = rhs(n - 1)/diag(n - 1)
        do i = n - 2, 2, -1
            sp%m(i) = (rhs(i) - h(i)*sp%m(i + 1))/diag(i)
        end do
    end subroutine spline_set

    !> Value, first and second derivative of a spline; linear extrapolation
    !! with the end slope outside the table.
    pure subroutine spline_eval(sp, tt, y, yd, ydd)
        type(spline_t), intent(in) :: sp   !! the spline from spline_set
        real(wp), intent(in) :: tt         !! time [s]
        real(wp), intent(out) :: y         !! value at tt
        real(wp), intent(out) :: yd        !! first derivative dy/dt
        real(wp), intent(out) :: ydd       !! second derivative (0 outside the knots)
        integer :: i, n
        real(wp) :: h, a, b, tc
        n = size(sp%t)
        if (n == 1) then
            y = sp%y(1); yd = zero; ydd = zero; return
        end if
        tc = min(max(tt, sp%t(1)), sp%t(n))
        i = table_segment(sp%t, tc)
        h = sp%t(i + 1) - sp%t(i)
        a = (sp%t(i + 1) - tc)/h
        b = (tc - sp%t(i))/h
        y = a*sp%y(i) + b*sp%y(i + 1) + ((a**3 - a)*sp%m(i) + (b**3 - b)*sp%m(i + 1))*h**2/6.0_wp
        yd = (sp%y(i + 1) - sp%y(i))/h - (3.0_wp*a**2 - one)/6.0_wp*h*sp%m(i) &
             + (3.0_wp*b**2 - one)/6.0_wp*h*sp%m(i + 1)
        ydd = a*sp%m(i) + b*sp%m(i + 1)
        if (tt /= tc) then
            y = y + yd*(tt - tc)
            ydd = zero
        end if
    end subroutine spline_eval

    !> Linear interpolation of the samples (xp, fp) at x, the end values
    !! held outside [xp(1), xp(n)] (numpy.interp); x and xp increasing.
    pure function resample(x, xp, fp) result(f)
        real(wp), intent(in) :: x(:)    !! where the values are wanted, increasing
        real(wp), intent(in) :: xp(:)   !! sample abscissae, increasing
        real(wp), intent(in) :: fp(:)   !! sample values at xp
        real(wp) :: f(size(x))
        integer :: i, j
        j = 1
        do i = 1, size(x)
            if (x(i) <= xp(1)) then
                f(i) = fp(1)
            else if (x(i) >= xp(size(xp))) then
                f(i) = fp(size(fp))
            else
                do while (xp(j + 1) < x(i))
                    j = j + 1
                end do
                f(i) = fp(j) + (fp(j + 1) - fp(j))*(x(i) - xp(j))/(xp(j + 1) - xp(j))
            end if
        end do
    end function resample

    !> Derivative of samples x taken every dt: central differences inside,
    !! one-sided at the two ends (numpy.gradient); at least two samples.
    pure function gradient(x, dt) result(d)
        real(wp), intent(in) :: x(:)    !! the samples
        real(wp), intent(in) :: dt      !! sample interval
        real(wp) :: d(size(x))
        integer :: n
        n = size(x)
        d(2:n - 1) = (x(3:n) - x(1:n - 2))/(2*dt)
        d(1) = (x(2) - x(1))/dt
        d(n) = (x(n) - x(n - 1))/dt
    end function gradient

end module hn_tables
