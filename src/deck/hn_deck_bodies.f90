!> The body cards of a deck: BODY, BODYPI and JOINT make the body tree;
!! the LOCK and NEUTRAL cards (hn_deck_coordinates) and the scene cards
!! (hn_deck_scene) are read in their place while it is built (`body_cards`).
module hn_deck_bodies
    use hn_kinds, only: wp, zero, msglen
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t, int_str, upper
    use hn_tree, only: body_tree_t, tree_allocate, tree_build, name_len
    use hn_model, only: model_init
    use hn_deck_state, only: big_length, card_t, body_map_t, body_ref
    use hn_deck_scene, only: scene_cards
    use hn_deck_coordinates, only: lock_card, neutral_card
    implicit none
    private

    public :: body_cards

contains

    !> BODY, BODYPI, JOINT, LOCK, NEUTRAL, SCENE, MERGE: the tree tables.
    subroutine body_cards(rd, cards, cs, bnames, bmap)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_t), intent(in) :: cards(:)  !! the deck's cards with their continuation cards (group_cards)
        type(case_t), intent(inout) :: cs  !! the run case the cards fill
        character(len=10), allocatable, intent(out) :: bnames(:)  !! the names of the deck's bodies, in deck order
        type(body_map_t), intent(out) :: bmap  !! where each deck body went (MERGE), what locked its coordinates
        character(len=10), allocatable :: pnames(:)
        integer, allocatable :: bline(:)
        integer :: nb, k, kb, i, f, p, stat, bad
        character(len=msglen) :: msg
        real(wp) :: v
        type(body_tree_t) :: tree

        nb = count(cards%key == 'BODY')
        if (nb == 0) then
            call rd%fail(rd%top//': the deck has no BODY card; expected at least one body')
            return
        end if
        allocate (bnames(nb), pnames(nb), bline(nb), bmap%locked_by(6, nb))
        bmap%locked_by = 0
        call tree_allocate(cs%model%tree, nb)
        kb = 0
        do k = 1, size(cards)
            if (cards(k)%key /= 'BODY') cycle
            kb = kb + 1
            i = cards(k)%first
            bline(kb) = i
            call body_name(rd, i, bnames(1:kb - 1), bnames(kb))
            if (rd%failed()) return
            call rd%name(i, 2, 'parent body', pnames(kb))
            call rd%real(i, 3, 'mass', 'kg', cs%model%tree%mass(kb), 1.0e-6_wp, 1.0e4_wp)
            cs%model%tree%inertia(:, :, kb) = zero
            do f = 1, 3
                call rd%real(i, 3 + f, 'principal inertia', 'kg m^2', v, 1.0e-12_wp, 1.0e4_wp)
                cs%model%tree%inertia(f, f, kb) = v
            end do
            cs%model%tree%name(kb) = bnames(kb)
        end do
        if (rd%failed()) return
        do kb = 1, nb
            if (pnames(kb) == 'R' .or. pnames(kb) == 'INERTIAL') then
                cs%model%tree%parent(kb) = 0
            else
                p = findloc(bnames, pnames(kb), dim=1)
                if (p == 0) then
                    call rd%fail(rd%context(bline(kb), 2, 'parent body')//': found "'//trim(pnames(kb))// &
                                 '"; expected R (inertial frame) or a body defined on a BODY card')
                    return
                end if
                cs%model%tree%parent(kb) = p
            end if
        end do
        call check_roots(rd, cs%model%tree%parent, bnames, bline)
        if (rd%failed()) return

        do k = 1, size(cards)
            i = cards(k)%first
            select case (cards(k)%key)
            case ('BODYPI')
                kb = body_ref(rd, i, 1, 'body', bnames, .false.)
                if (rd%failed()) return
                call rd%real(i, 2, 'product of inertia Ixy', 'kg m^2', v, -1.0e4_wp, 1.0e4_wp)
                cs%model%tree%inertia(1, 2, kb) = v; cs%model%tree%inertia(2, 1, kb) = v
                call rd%real(i, 3, 'product of inertia Ixz', 'kg m^2', v, -1.0e4_wp, 1.0e4_wp)
                cs%model%tree%inertia(1, 3, kb) = v; cs%model%tree%inertia(3, 1, kb) = v
                call rd%real(i, 4, 'product of inertia Iyz', 'kg m^2', v, -1.0e4_wp, 1.0e4_wp)
                cs%model%tree%inertia(2, 3, kb) = v; cs%model%tree%inertia(3, 2, kb) = v
            case ('JOINT')
                kb = body_ref(rd, i, 1, 'body', bnames, .false.)
                if (rd%failed()) return
                do f = 1, 3
                    call rd%real(i, 1 + f, 'joint point in parent', 'm', v, -big_length, big_length)
                    cs%model%tree%joint_parent(f, kb) = v
                    call rd%real(i, 4 + f, 'joint point in body', 'm', v, -big_length, big_length)
                    cs%model%tree%joint_child(f, kb) = v
                end do
            case ('LOCK')
                call lock_card(rd, i, bnames, cs, bmap%locked_by)
            case ('NEUTRAL')
                call neutral_card(rd, i, bnames, cs)
            end select
            if (rd%failed()) return
        end do

        call tree_build(cs%model%tree, stat, msg, bad)
        if (stat /= 0) then
            call rd%fail(body_place(bad)//': '//trim(msg))
            return
        end if
        allocate (bmap%new(nb), bmap%shift(3, nb), bmap%merged_by(nb))
        bmap%new = [(k, k=1, nb)]
        bmap%shift = zero
        bmap%merged_by = 0
        call scene_cards(rd, cards, cs, bnames, bmap)
        if (rd%failed()) return
        call tree_build(cs%model%tree, stat, msg)
        if (stat /= 0) then
            call rd%fail(rd%where(cards(findloc(cards%key, 'MERGE', dim=1, back=.true.))%first)// &
                         ' (MERGE cards): '//trim(msg))
            return
        end if
        tree = cs%model%tree       ! model_init takes the tree by value (its model argument is intent(out))
        call model_init(cs%model, tree)
    contains
        !> The BODY card of body kb (and its BODYPI card, if any) in messages.
        function body_place(kbad) result(s)
            integer, intent(in) :: kbad
            character(len=:), allocatable :: s
            integer :: kk
            if (kbad < 1 .or. kbad > nb) then
                s = rd%top//' (BODY cards)'
                return
            end if
            s = rd%where(bline(kbad))//' (BODY card '//trim(bnames(kbad))
            do kk = 1, size(cards)
                if (cards(kk)%key /= 'BODYPI') cycle
                if (upper(rd%raw(cards(kk)%first, 1)) == bnames(kbad)) &
                    s = s//'; its BODYPI card is at '//rd%where(cards(kk)%first)
            end do
            s = s//')'
        end function body_place
    end subroutine body_cards

    !> The name of a new body on BODY card image i: not a name of the
    !! inertial frame, not reserved, not too long, not a name already used.
    subroutine body_name(rd, i, earlier, name)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i                      !! the BODY card image
        character(len=10), intent(in) :: earlier(:)   !! the bodies defined before it
        character(len=10), intent(out) :: name        !! its name
        call rd%name(i, 1, 'body name', name)
        if (rd%failed()) return
        if (name == 'R' .or. name == 'INERTIAL') then
            call rd%fail(rd%context(i, 1, 'body name')//': found "'//trim(name)//'", which names the '// &
                         'inertial frame (R, alias INERTIAL); expected another name')
        else if (name == 'ALL') then
            call rd%fail(rd%context(i, 1, 'body name')//': found "ALL", a reserved word (LOCK ALL '// &
                         'means every body); expected another name')
        else if (len_trim(name) > name_len) then
            call rd%fail(rd%context(i, 1, 'body name')//': found "'//trim(name)//'"; expected at most 12 characters')
        else if (any(earlier == name)) then
            call rd%fail(rd%context(i, 1, 'body name')//': body "'//trim(name)// &
                         '" is defined twice; expected a new name')
        end if
    end subroutine body_name

    !> Exactly one body hangs from R, and following parents from any body
    !! reaches it: errors name the BODY cards concerned.
    subroutine check_roots(rd, parent, bnames, bline)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: parent(:), bline(:)
        character(len=10), intent(in) :: bnames(:)
        integer :: nroot, k, p, steps, r1
        character(len=:), allocatable :: loop
        nroot = count(parent == 0)
        if (nroot > 1) then
            r1 = findloc(parent, 0, dim=1)
            k = findloc(parent(r1 + 1:), 0, dim=1) + r1
            call rd%fail(rd%context(bline(k), 2, 'parent body')//': body '//trim(bnames(k))// &
                         ' has parent R, and so has body '//trim(bnames(r1))//' ('//rd%where(bline(r1))//'); '// &
                         trim(int_str(nroot))//' bodies have parent R; expected exactly one root body '// &
                         '(the tree hangs from one body)')
            return
        end if
        ! a body whose chain of parents does not reach R within nb steps lies on or hangs from a loop
        do k = 1, size(parent)
            p = k
            steps = 0
            do while (p /= 0 .and. steps <= size(parent))
                p = parent(p)
                steps = steps + 1
            end do
            if (p == 0) cycle
            ! walk on until a body repeats: that body is on the loop
            p = k
            do steps = 1, size(parent)
                p = parent(p)
            end do
            loop = trim(bnames(p))
            r1 = parent(p)
            do while (r1 /= p)
                loop = loop//' -> '//trim(bnames(r1))
                r1 = parent(r1)
            end do
            loop = loop//' -> '//trim(bnames(p))
            if (nroot == 0) then
                call rd%fail(rd%context(bline(p), 2, 'parent body')//': 0 bodies have parent R; body '// &
                             trim(bnames(p))//' lies on a loop of parents ('//loop//'); expected an open tree '// &
                             'hanging from one body with parent R')
            else
                call rd%fail(rd%context(bline(p), 2, 'parent body')//': body '//trim(bnames(p))// &
                             ' lies on a loop of parents ('//loop//'); expected an open tree hanging from one '// &
                             'body with parent R')
            end if
            return
        end do
        if (nroot == 0) call rd%fail(rd%top//': no BODY card has parent R; expected exactly one root body')
    end subroutine check_roots

end module hn_deck_bodies
