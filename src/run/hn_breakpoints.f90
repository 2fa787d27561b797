!> The times at which the inputs of a case have a kink or a jump (knots of
!! prescribed-motion tables, applied-load tables and muscle activation
!! tables): the run lets its steps end there.
module hn_breakpoints
    use hn_kinds, only: wp
    use hn_case, only: case_t
    use hn_motion, only: motion_breakpoints
    implicit none
    private

    public :: case_breakpoints

contains

    !> Times in (t_start, t_end) where an input table has a kink or jump:
    !! knots of prescribed-motion tables, applied-load tables and muscle
    !! activation tables; sorted, without repeats.
    function case_breakpoints(cs) result(tb)
        type(case_t), intent(in) :: cs
        real(wp), allocatable :: tb(:), all(:)
        integer :: j, e, i, n
        allocate (all(0))
        do j = 1, size(cs%model%prescribed)
            if (cs%model%prescribed(j)) all = [all, motion_breakpoints(cs%model%motion(j))]
        end do
        do e = 1, size(cs%model%applied)
            all = [all, cs%model%applied(e)%magnitude%t]
        end do
        do e = 1, size(cs%model%tables)
            all = [all, cs%model%tables(e)%t]
        end do
        all = pack(all, all > cs%t_start .and. all < cs%t_end)
        ! insertion sort, then drop repeats
        do i = 2, size(all)
            j = i
            do while (j > 1)
                if (all(j - 1) <= all(j)) exit
                all([j - 1, j]) = all([j, j - 1])
                j = j - 1
            end do
        end do
        allocate (tb(size(all)))
        n = 0
        do i = 1, size(all)
            if (n > 0) then
                if (all(i) - tb(n) <= 1.0e-12_wp) cycle
            end if
            n = n + 1
            tb(n) = all(i)
        end do
        tb = tb(1:n)
    end function case_breakpoints

end module hn_breakpoints
