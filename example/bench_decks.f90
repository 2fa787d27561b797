!> Deck helpers shared by the benchmark examples.
module bench_decks
    use hn_kinds, only: wp
    implicit none
    private

    public :: copy_with_stiffen, delete_file

contains

    !> A copy of deck `src` in `dst` with every element stiffness times
    !! `factor` (a STIFFEN card appended).
    subroutine copy_with_stiffen(src, dst, factor)
        character(len=*), intent(in) :: src, dst   !! deck files
        real(wp), intent(in) :: factor             !! stiffness factor
        character(len=256) :: line
        integer :: a, b, ios
        open (newunit=a, file=src, status='old', action='read')
        open (newunit=b, file=dst, status='replace', action='write')
        do
            read (a, '(a)', iostat=ios) line
            if (ios /= 0) exit
            write (b, '(a)') trim(line)
        end do
        write (b, '(a,f10.1)') 'STIFFEN   ', factor
        close (a)
        close (b)
    end subroutine copy_with_stiffen

    !> Delete file fname if it exists.
    subroutine delete_file(fname)
        character(len=*), intent(in) :: fname   !! file name
        integer :: u, ios
        open (newunit=u, file=fname, status='old', iostat=ios)
        if (ios == 0) close (u, status='delete')
    end subroutine delete_file

end module bench_decks
