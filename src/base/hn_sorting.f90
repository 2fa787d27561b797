!> Sorting by permutation: the permutation that orders small real arrays (the
!! Nelder-Mead simplex of the calibration, medians of the benchmarks) and
!! texts of any number (the deck's names, to find repeats in n log n).
module hn_sorting
    use hn_kinds, only: wp
    implicit none
    private

    public :: sort_index, sort_index_text, merge_times

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

    !> Indices that sort the texts v ascending (merge sort: stable, n log n):
    !! v(sort_index_text(v)) is v in ascending order, equal texts in their
    !! original order.
    pure function sort_index_text(v) result(idx)
        character(len=*), intent(in) :: v(:)    !! the texts
        integer :: idx(size(v))
        integer :: tmp(size(v))
        integer :: n, width, lo, mid, hi, i, j, k
        logical :: take_left
        n = size(v)
        idx = [(i, i=1, n)]
        width = 1
        do while (width < n)
            do lo = 1, n, 2*width
                mid = min(lo + width - 1, n)
                hi = min(lo + 2*width - 1, n)
                i = lo; j = mid + 1
                do k = lo, hi
                    take_left = i <= mid      ! (no short-circuit in Fortran: j is tested apart)
                    if (take_left .and. j <= hi) take_left = lle(v(idx(i)), v(idx(j)))
                    if (take_left) then
                        tmp(k) = idx(i); i = i + 1
                    else
                        tmp(k) = idx(j); j = j + 1
                    end if
                end do
            end do
            idx = tmp
            width = 2*width
        end do
    end function sort_index_text

    !> The ascending times a and b merged, a time within tol of one kept listed once.
    pure function merge_times(a, b, tol) result(c)
        real(wp), intent(in) :: a(:)     !! ascending times [s]
        real(wp), intent(in) :: b(:)     !! ascending times [s]
        real(wp), intent(in) :: tol      !! times closer than this are one [s]
        real(wp), allocatable :: c(:)
        integer :: i, j, n
        allocate (c(size(a) + size(b)))
        i = 1; j = 1; n = 0
        do while (i <= size(a) .or. j <= size(b))
            n = n + 1
            if (j > size(b)) then
                c(n) = a(i); i = i + 1
            else if (i > size(a)) then
                c(n) = b(j); j = j + 1
            else if (abs(a(i) - b(j)) <= tol) then
                c(n) = a(i); i = i + 1; j = j + 1
            else if (a(i) < b(j)) then
                c(n) = a(i); i = i + 1
            else
                c(n) = b(j); j = j + 1
            end if
        end do
        c = c(1:n)
    end function merge_times

end module hn_sorting
