!> Deck helpers shared by the benchmark examples.
module bench_decks
    use hn_kinds, only: wp, msglen
    use hn_case, only: case_t
    use hn_deck, only: read_case
    implicit none
    private

    public :: copy_with_stiffen, delete_file, read_stiffened_case

contains

    !> Read deck `deck`, with every element stiffness times `factor` when
    !! factor > 0 (by way of the scratch file `tmp`); stops on a deck error.
    subroutine read_stiffened_case(deck, tmp, factor, cs)
        character(len=*), intent(in) :: deck      !! the deck file
        character(len=*), intent(in) :: tmp       !! scratch file for the stiffened copy
        real(wp), intent(in) :: factor            !! stiffness factor (0: the deck as it is)
        type(case_t), intent(out) :: cs           !! the case read
        integer :: stat
        character(len=msglen) :: msg
        if (factor > 0) then
            call copy_with_stiffen(deck, tmp, factor)
            call read_case(tmp, tmp, cs, stat, msg)
            call delete_file(tmp)
        else
            call read_case(deck, deck, cs, stat, msg)
        end if
        if (stat /= 0) error stop trim(msg)
    end subroutine read_stiffened_case

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
