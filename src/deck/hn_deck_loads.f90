!> The load cards of a deck: FORCE and COUPLE, applied loads from a table
!! (`load_cards`), and STIFFEN, a factor on element stiffnesses
!! (`stiffen_cards`, after every element card).
module hn_deck_loads
    use hn_kinds, only: wp, zero
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t
    use hn_applied, only: applied_load_t, applied_force, applied_couple, frame_body, frame_inertial
    use hn_rotation, only: norm3
    use hn_deck_state, only: deck_state_t, big_length, card_t, family_ref, body_ref, table_ref
    implicit none
    private

    public :: load_cards, stiffen_cards

contains

    !> FORCE and COUPLE cards (moved onto merged bodies).
    subroutine load_cards(rd, st, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(deck_state_t), intent(in) :: st  !! the deck's cards, bodies (names, where each went) and tables
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        type(applied_load_t) :: al
        integer :: k, i, f, it, nal
        character(len=10) :: s
        deallocate (cs%model%applied)
        allocate (cs%model%applied(count(st%cards%key == 'FORCE' .or. st%cards%key == 'COUPLE')))
        nal = 0
        do k = 1, size(st%cards)
            if (st%cards(k)%key /= 'FORCE' .and. st%cards(k)%key /= 'COUPLE') cycle
            i = st%cards(k)%first
            al = applied_load_t()
            al%kind = merge(applied_force, applied_couple, st%cards(k)%key == 'FORCE')
            al%body = body_ref(rd, i, 1, 'body', st%bnames, .false.)
            call rd%name(i, 2, 'frame', s)
            if (rd%failed()) return
            select case (s)
            case ('R', 'INERTIAL'); al%frame = frame_inertial
            case ('BODY'); al%frame = frame_body
            case default
                call rd%fail(rd%context(i, 2, 'frame')//': found "'//trim(s)//'"; expected R (inertial) or BODY')
                return
            end select
            it = table_ref(rd, i, 3, st%tabs)
            do f = 1, 3
                call rd%real(i, 3 + f, 'direction', '-', al%direction(f), -1.0e6_wp, 1.0e6_wp)
            end do
            if (rd%failed()) return
            if (norm3(al%direction) == zero) then
                call rd%fail(rd%where(i)//', columns 41-70 ('//trim(st%cards(k)%key)//' card, fields F4-F6 '// &
                             '''direction''): found a zero vector; expected a direction')
                return
            end if
            al%direction = al%direction/norm3(al%direction)
            al%magnitude = st%tabs(it)%tab
            if (al%kind == applied_force) then
                do f = 1, 3
                    call rd%real(i + 1, f, 'point of application', 'm', al%point(f), -big_length, big_length)
                end do
            end if
            if (rd%failed()) return
            al%point = al%point + st%bmap%shift(:, al%body)
            al%body = st%bmap%new(al%body)
            nal = nal + 1; cs%model%applied(nal) = al
        end do
        cs%model%applied = cs%model%applied(1:nal)
    end subroutine load_cards

    !> STIFFEN factor [family]: multiply element stiffnesses (disc d1, d2 and
    !! G, ligament l1 and l2, muscle m1, spring stiffness) by a factor, for
    !! every family or the one named; damping-to-stiffness ratios of the discs
    !! are kept.
    subroutine stiffen_cards(rd, cards, cs)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        integer :: k, i, fam, f
        real(wp) :: fac
        character(len=10) :: s
        do k = 1, size(cards)
            if (cards(k)%key /= 'STIFFEN') cycle
            i = cards(k)%first
            call rd%real(i, 1, 'stiffness factor', '-', fac, 1.0e-6_wp, 1.0e6_wp)
            call rd%name(i, 2, 'element family', s, optional_blank=.true.)
            if (rd%failed()) return
            fam = 0
            if (len_trim(s) > 0) fam = family_ref(rd, i, s)
            if (rd%failed()) return
            do f = 1, size(cs%model%family)
                if (fam == 0 .or. fam == f) call cs%model%family(f)%f%stiffen(fac)
            end do
        end do
    end subroutine stiffen_cards

end module hn_deck_loads
