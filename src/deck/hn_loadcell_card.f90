!> The LOADCELL card (docs/deck-format.md): a section whose load is a set of
!! channels -- the force and moment the rest of the system exerts on the
!! subtree of a body, about a point (hn_sections).
!!
!!   LOADCELL  F1 name     1 to 7 characters (channels NAME_FX ... NAME_JMZ)
!!             F2 body     the body at the base of the subtree
!!             F3-F5 point x, y, z in the frame body's axes from its mass
!!                         centre [m]; all three blank: the body's joint point
!!             F6 frame    the body whose axes give the point and the load's
!!                         components (the cell's mounting); blank: the body
module hn_loadcell_card
    use hn_kinds, only: wp
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t
    use hn_deck_state, only: card_t, body_map_t, body_ref
    use hn_sections, only: section_t, section_name_len
    implicit none
    private

    public :: loadcell_cards

    real(wp), parameter :: point_max = 10.0_wp   !! largest point coordinate accepted [m]

contains

    !> Every LOADCELL card of the deck into cs%loadcells (in deck order); a
    !! bad card is a located error (rd%fail).
    subroutine loadcell_cards(rd, cards, cs, bnames, bmap)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        type(case_t), intent(inout) :: cs  !! the run case: loadcells set
        character(len=10), intent(in) :: bnames(:)  !! the names of the deck's bodies, in deck order
        type(body_map_t), intent(in) :: bmap  !! where each deck body went (MERGE)
        type(section_t) :: sec
        integer, allocatable :: lines(:)
        character(len=10) :: s
        integer :: k, i, kb, f, other
        allocate (cs%loadcells(0), lines(0))
        do k = 1, size(cards)
            if (rd%failed()) return
            if (cards(k)%key /= 'LOADCELL') cycle
            i = cards(k)%first
            call rd%name(i, 1, 'load-cell name', s)
            if (rd%failed()) return
            if (len_trim(s) > section_name_len) then
                call rd%fail(rd%context(i, 1, 'load-cell name')//': found "'//trim(s)//'"; expected a name of '// &
                             'at most 7 characters (its channels are NAME_FX ... NAME_JMZ)')
                return
            end if
            do other = size(cs%loadcells), 0, -1
                if (other == 0) exit
                if (cs%loadcells(other)%name == s(1:section_name_len)) exit
            end do
            if (other > 0) then
                call rd%fail(rd%context(i, 1, 'load-cell name')//': found "'//trim(s)//'", the name of the load '// &
                             'cell at '//rd%where(lines(other))//'; expected a new name')
                return
            end if
            sec = section_t()
            sec%name = s(1:section_name_len)
            sec%body = tree_body(i, 2, 'body')
            sec%frame = sec%body
            if (.not. rd%is_blank(i, 6)) sec%frame = tree_body(i, 6, 'frame body')
            if (rd%failed()) return
            if (any([(.not. rd%is_blank(i, f), f=3, 5)])) then
                sec%at_joint = .false.
                do f = 3, 5
                    call rd%real(i, f, 'point '//achar(iachar('x') + f - 3), 'm', sec%point(f - 2), -point_max, point_max)
                end do
                if (rd%failed()) return
                sec%point = bmap%length*(sec%point + bmap%shift(:, kb))   ! deck frame -> tree frame (MERGE, OCCUPANT)
            end if
            cs%loadcells = [cs%loadcells, sec]
            lines = [lines, i]
        end do
    contains
        !> The tree body a field names (kb: its deck body); a body MERGE
        !! absorbed is refused.
        integer function tree_body(i, f, what) result(k)
            integer, intent(in) :: i, f
            character(len=*), intent(in) :: what
            k = 1
            kb = body_ref(rd, i, f, what, bnames, .false.)
            if (rd%failed()) return
            if (bmap%merged_by(kb) > 0) then
                call rd%fail(rd%context(i, f, what)//': found "'//trim(bnames(kb))//'", merged into another '// &
                             'body by the MERGE card at '//rd%where(bmap%merged_by(kb))//'; expected a body of the tree')
                return
            end if
            k = bmap%new(kb)
        end function tree_body
    end subroutine loadcell_cards

end module hn_loadcell_card
