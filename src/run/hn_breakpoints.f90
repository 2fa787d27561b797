!> The times at which the inputs of a case change abruptly enough for the
!! run to end a step there and restart the integrator: the corners of the
!! input tables. Every input table of a case is piecewise linear in a
!! quantity that enters the equations of motion directly (the acceleration
!! of a prescribed coordinate, an applied force or couple, the input tables
!! of an element family, `input_tables`: the muscles' activations), so at
!! each knot the right-hand side keeps its value and changes its slope. A
!! knot is
!!   smooth  when the slope changes little against the table's range over
!!           the knot's neighbourhood (sampled smooth data, such as the NBDL
!!           sled tables every 1 ms): the error control of the method takes
!!           it in its stride, no landing, no restart;
!!   corner  when it changes a lot (the start, peak and end of an impact
!!           pulse such as case 6-5's triangle): steps land on it exactly and
!!           the method restarts there.
!! Position tables (natural cubic splines, linear outside) have continuous
!! accelerations everywhere: no corners.
module hn_breakpoints
    use hn_kinds, only: wp, zero
    use hn_case, only: case_t
    use hn_motion, only: motion_kind_accel, motion_kind_rate
    use hn_sorting, only: sort_index
    use hn_tables, only: table_t
    implicit none
    private

    public :: case_breakpoints, table_corners

    !> A knot is a corner when |change of slope| x (shorter neighbouring
    !! interval) exceeds this fraction of the table's range. Sampled smooth
    !! inputs stay below 0.08 (NBDL 15 g tables: 0.043 for T1 x, 0.077 for
    !! T1 z), an impact pulse's corners are of order 1 (case 6-5: 1.0-1.5).
    real(wp), parameter :: corner_fraction = 0.25_wp
    !> Knots closer than this are one breakpoint [s].
    real(wp), parameter :: same_time = 1.0e-12_wp

contains

    !> Times in (t_start, t_end) where an input table has a corner: knots of
    !! prescribed acceleration tables, applied-load tables and the element
    !! families' input tables (muscle activations); sorted, without repeats.
    function case_breakpoints(cs) result(tb)
        type(case_t), intent(in) :: cs   !! the run case (prescribed motions, load and activation tables, times)
        real(wp), allocatable :: tb(:), all(:)
        type(table_t), allocatable :: tables(:)
        integer :: j, e, i, n, f
        allocate (all(0))
        do j = 1, size(cs%model%prescribed)
            if (.not. cs%model%prescribed(j)) cycle
            if (any(cs%model%motion(j)%kind == [motion_kind_accel, motion_kind_rate])) &
                all = [all, table_corners(cs%model%motion(j)%acc%t, cs%model%motion(j)%acc%y)]
        end do
        do e = 1, size(cs%model%applied)
            all = [all, table_corners(cs%model%applied(e)%magnitude%t, cs%model%applied(e)%magnitude%y)]
        end do
        do f = 1, size(cs%model%family)
            tables = cs%model%family(f)%f%input_tables()
            do e = 1, size(tables)
                all = [all, table_corners(tables(e)%t, tables(e)%y)]
            end do
        end do
        all = pack(all, all > cs%t_start .and. all < cs%t_end)
        all = all(sort_index(all))   ! ascending, then drop repeats
        allocate (tb(size(all)))
        n = 0
        do i = 1, size(all)
            if (n > 0) then
                if (all(i) - tb(n) <= same_time) cycle
            end if
            n = n + 1
            tb(n) = all(i)
        end do
        tb = tb(1:n)
    end function case_breakpoints

    !> The corners of a piecewise-linear table y(t) held constant outside
    !! its times (slope zero before the first and after the last knot); a
    !! step (two knots at one time) is a corner.
    pure function table_corners(t, y) result(tc)
        real(wp), intent(in) :: t(:)   !! knot times, increasing [s]
        real(wp), intent(in) :: y(:)   !! values at the knots
        real(wp), allocatable :: tc(:)
        logical :: corner(size(t))
        real(wp) :: range, sl, sr, tau
        integer :: i, n
        n = size(t)
        corner = .false.
        range = zero
        if (n > 0) range = maxval(y) - minval(y)
        if (n > 1 .and. range > zero) then
            do i = 1, n
                if (i > 1) corner(i) = t(i) <= t(i - 1)
                if (i < n) corner(i) = corner(i) .or. t(i + 1) <= t(i)
                if (corner(i)) cycle      ! a step
                sl = zero; sr = zero; tau = huge(1.0_wp)
                if (i > 1) then
                    sl = (y(i) - y(i - 1))/(t(i) - t(i - 1))
                    tau = t(i) - t(i - 1)
                end if
                if (i < n) then
                    sr = (y(i + 1) - y(i))/(t(i + 1) - t(i))
                    tau = min(tau, t(i + 1) - t(i))
                end if
                corner(i) = abs(sr - sl)*tau > corner_fraction*range
            end do
        end if
        tc = pack(t, corner)
    end function table_corners

end module hn_breakpoints
