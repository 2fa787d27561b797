!> The CRITERIA card (docs/deck-format.md): which occupant's reference
!! values the injury criteria are compared with, and the frame of NIC's
!! x-accelerations.
!!
!!   CRITERIA  F1 occupant   H50M (default), H05F
!!             F2 NIC frame  INERTIAL (default: global x) or HEAD (head x axis)
!!
!! Blank fields keep the defaults; without the card the criteria are those
!! of earlier versions (Hybrid III 50th male, NIC in inertial axes).
module hn_criteria_card
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t
    use hn_injury, only: occupants
    implicit none
    private

    public :: criteria_card

contains

    !> Read the CRITERIA card at card image i into cs%occupant and
    !! cs%nic_frame; an unknown name is a located error (rd%fail).
    subroutine criteria_card(rd, i, cs)
        type(deck_reader_t), intent(inout) :: rd   !! the deck being read
        integer, intent(in) :: i                   !! card image number of the CRITERIA card
        type(case_t), intent(inout) :: cs          !! the case: occupant and nic_frame set
        character(len=8) :: v
        character(len=4) :: codes(size(occupants))
        codes = occupants%code                 ! a contiguous array for rd%choice
        if (rd%failed()) return
        if (.not. rd%is_blank(i, 1)) then
            call rd%choice(i, 1, 'occupant', codes, v)
            if (rd%failed()) return
            cs%occupant = v(1:4)
        end if
        if (.not. rd%is_blank(i, 2)) then
            call rd%choice(i, 2, 'NIC frame', [character(len=8) :: 'INERTIAL', 'HEAD'], v)
            if (rd%failed()) return
            cs%nic_frame = v
        end if
    end subroutine criteria_card

end module hn_criteria_card
