!> Sorting of small real arrays: the permutation that orders them (the
!! Nelder-Mead simplex of the calibration, medians of the benchmarks).
module hn_sorting
    use hn_kinds, only: wp
    implicit none
    private

    public :: sort_index

contains

    !> Indices that sort v ascending (insertion sort; stable): v(sort_index(v))
    !! is v in ascending order.
    pure function sort_index(v) result(idx)
        real(wp), intent(in) :: v(:)    !! the values
        integer :: idx(size(v))
        integer :: i, j, k
        idx = [(i, i=1, size(v))]
        do i = 2, size(v)
            k = idx(i)
            j = i - 1
            do while (j >= 1)
                if (v(idx(j)) <= v(k)) exit
                idx(j + 1) = idx(j)
                j = j - 1
            end do
            idx(j + 1) = k
        end do
    end function sort_index

end module hn_sorting
