!> What an element family needs to read its own deck cards: the deck's
!! cards (`card_t`), bodies (their names and where each went, `body_map_t`)
!! and named tables (`named_table_t`), together the `deck_state_t` the card
!! groups of the deck reader share, and, in `card_context_t`, what the
!! earlier cards made of the model (the reduced tree, the prescribed
!! motions, the run's time span) and what the families report back (the
!! elements dropped with both ends on one merged body, scene notes). The
!! located references of one card to a body, a coordinate or a table, the
!! coordinate units, and the attachment of a point-to-point element
!! (`line_card`) are here too, so a family module can read its cards with
!! the field access of hn_deck_reader and no module of src/deck/. `card_t`,
!! `ncont_optional` and `continued` are the card engine's (hn_card_engine),
!! re-exported.
!!
!! `family_card_t` is one card of a family as its registry entry
!! (hn_family_registration) lists it: key, family, continuation cards, when in the reading it is
!! read (`card_first`, `card_in_order`, `card_last`), which repeats of it
!! the deck refuses (`unique_element`, `unique_name`, `unique_coordinate`)
!! and whether its fields F1, F2 name a body and one of its coordinates.
module hn_element_cards
    use hn_kinds, only: wp, zero, one, deg, g_std
    use hn_deck_reader, only: deck_reader_t
    use hn_card_engine, only: card_t, ncont_optional, continued
    use hn_tables, only: table_t
    use hn_tree, only: body_tree_t
    use hn_motion, only: motion_t, motion_eval
    use hn_rotation, only: norm3
    use hn_line_elements, only: line_attach_t
    implicit none
    private

    public :: card_t, body_map_t, named_table_t, deck_state_t, card_context_t, family_card_t
    public :: coord_names, big_length, big_modulus
    public :: body_ref, coord_ref, table_ref, active_coordinate, locked_error, unit_of, unit_factor, unit_limit
    public :: distinct_bodies, map_ends, line_points, line_card, continued

    !> The coordinates of a body in deck order.
    character(len=2), parameter :: coord_names(6) = ['TX', 'TY', 'TZ', 'RX', 'RY', 'RZ']
    real(wp), parameter :: big_length = 10.0_wp     !! largest coordinate of a point [m]
    real(wp), parameter :: big_modulus = 1.0e13_wp  !! largest modulus or stiffness accepted

    !> When a family's card is read: before the other element cards (what
    !! they name, e.g. ACTIVATE histories), in deck order with them, or
    !! after them (what adds to elements read before, e.g. VIA points).
    integer, parameter, public :: card_first = 1, card_in_order = 2, card_last = 3

    !> Which repeats of a family's card the deck refuses (at the later card,
    !! naming the earlier): none; the element name in F1 used by another
    !! card of any family with this rule (one namespace of element names);
    !! the name in F1 used by another card of the same name; a second card
    !! of the same name for the body and coordinate in F1, F2.
    integer, parameter, public :: unique_none = 0, unique_element = 1, unique_name = 2, unique_coordinate = 3

    !> A family card's continuation count that is not fixed (`ncont_optional`
    !! of the card engine): one continuation card when the next deck line's
    !! columns 1-10 are blank, none otherwise (an optional continuation card).
    public :: ncont_optional

    !> A deck card that belongs to a family: its key, its family (its
    !! place in the registry; 0 in the family's own entry), its continuation
    !! cards, when it is read (card_first, card_in_order, card_last), which
    !! repeats are refused, and its coordinate fields.
    type :: family_card_t
        character(len=8) :: key = ''
        integer :: family = 0
        integer :: ncont = 0                  !! continuation cards (ncont_optional: none or one)
        integer :: order = card_in_order
        integer :: unique = unique_none       !! which repeats the deck refuses (unique_none ... unique_coordinate)
        logical :: coordinate = .false.       !! F1 names a body, F2 one of its coordinates (CHANGE ... F7 names F2)
        character(len=16) :: what = 'name'    !! what F1 holds, in a unique_name message
    end type family_card_t

    !> Where each body named in the deck went: its number in the reduced
    !! tree and the shift of points given in its frame (MERGE); the card line
    !! of the MERGE that absorbed it (0: not absorbed); the factor on
    !! lengths of an OCCUPANT card (points on bodies, free lengths).
    type :: body_map_t
        integer, allocatable :: new(:)
        real(wp), allocatable :: shift(:, :)
        integer, allocatable :: merged_by(:)
        integer, allocatable :: locked_by(:, :)   !! (coordinate, deck body): the LOCK or SCENE card line that locked it (0: none)
        real(wp) :: length = one                  !! OCCUPANT: factor on points on bodies and free lengths
    end type body_map_t

    !> A named table of the deck.
    type :: named_table_t
        character(len=10) :: name = ''
        type(table_t) :: tab
        integer :: line = 0
        character(len=160) :: warning = ''   !! a scale that makes the table zero in effect
    end type named_table_t

    !> What the card groups pass along: the deck's cards, the names of its
    !! bodies and where each went, its named tables, its families' cards.
    type :: deck_state_t
        type(card_t), allocatable :: cards(:)
        character(len=10), allocatable :: bnames(:)   !! the deck's bodies, in deck order
        type(body_map_t) :: bmap
        type(named_table_t), allocatable :: tabs(:)
        !> the cards of the deck's element families, each with its family's
        !! number: the registry's and those of families brought to the deck
        !! (read_case's `families`); unallocated: the registry's, and the
        !! `deck_cards` of families added to the model in code
        type(family_card_t), allocatable :: fcards(:)
    end type deck_state_t

    !> What an element family reads its cards against: the deck's state,
    !! what the earlier cards made of the model, and what the families
    !! report back to the deck reader.
    type, extends(deck_state_t) :: card_context_t
        type(body_tree_t) :: tree                     !! the reduced tree (after MERGE, LOCK, SCENE)
        logical, allocatable :: prescribed(:)         !! (n) coordinates driven by a motion
        type(motion_t), allocatable :: motion(:)      !! (n) their motions
        real(wp) :: t_start = zero                    !! start of the run [s]
        real(wp) :: t_end = zero                      !! end of the run [s]
        integer :: ninternal = 0                      !! elements dropped so far: both ends on one merged body
        character(len=100), allocatable :: notes(:)   !! notes for the listing's scene section
    contains
        procedure :: ncards => context_ncards
        procedure :: needs_room => context_needs_room
        procedure :: add_note => context_add_note
        procedure :: pulse_onset => context_pulse_onset
    end type card_context_t


contains

    !> Number of the deck's cards named `key`.
    pure integer function context_ncards(ctx, key) result(n)
        class(card_context_t), intent(in) :: ctx   !! the context (its cards)
        character(len=*), intent(in) :: key        !! card name
        n = 0
        if (allocated(ctx%cards)) n = count(ctx%cards%key == key)
    end function context_ncards

    !> Whether a family about to read its first card `key` (none read yet)
    !! has less room than the deck's cards `key` need: the room is made once,
    !! and the deck's cards are counted only then (counting at every card
    !! makes reading a deck quadratic in its cards).
    pure logical function context_needs_room(ctx, key, nread, nitems) result(yes)
        class(card_context_t), intent(in) :: ctx   !! the context (its cards)
        character(len=*), intent(in) :: key        !! card name
        integer, intent(in) :: nread               !! the family's cards read so far
        integer, intent(in) :: nitems              !! the room it has
        yes = .false.
        if (nread == 0) yes = nitems < ctx%ncards(key)
    end function context_needs_room

    !> Append a line to the notes for the listing's scene section.
    pure subroutine context_add_note(ctx, text)
        class(card_context_t), intent(inout) :: ctx   !! the context; out: one note more
        character(len=*), intent(in) :: text          !! the note (at most 100 characters)
        character(len=100), allocatable :: tmp(:)
        integer :: n
        n = 0
        if (allocated(ctx%notes)) n = size(ctx%notes)
        allocate (tmp(n + 1))
        if (n > 0) tmp(1:n) = ctx%notes
        tmp(n + 1) = text
        call move_alloc(tmp, ctx%notes)
    end subroutine context_add_note

    !> First time (on a 0.1 ms grid) the prescribed translational
    !! acceleration of the root body exceeds 1 g; huge when it never does.
    pure function context_pulse_onset(ctx) result(t0)
        class(card_context_t), intent(in) :: ctx   !! the context (tree, motions, time span)
        real(wp) :: t0
        real(wp) :: t, a(3), x, xd
        integer :: root, m, j, n
        t0 = huge(one)
        root = findloc(ctx%tree%parent, 0, dim=1)
        do n = 0, nint((ctx%t_end - ctx%t_start)/1.0e-4_wp)
            t = ctx%t_start + n*1.0e-4_wp
            a = zero
            do m = 1, 3
                j = ctx%tree%dof_index(m, root)
                if (j == 0) cycle
                if (ctx%prescribed(j)) call motion_eval(ctx%motion(j), t, x, xd, a(m))
            end do
            if (norm3(a) > g_std) then
                t0 = t
                return
            end if
        end do
    end function context_pulse_onset

    !> Body named in field f (R allowed when allow_inertial: returns 0).
    integer function body_ref(rd, i, f, what, bnames, allow_inertial) result(kb)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        integer, intent(in) :: f  !! the field (F1 .. F7)
        character(len=*), intent(in) :: what  !! what the field holds (messages)
        character(len=10), intent(in) :: bnames(:)  !! the names of the deck's bodies, in deck order
        logical, intent(in) :: allow_inertial  !! R (the inertial frame) allowed, as body 0
        character(len=10) :: s
        kb = 1
        call rd%name(i, f, what, s)
        if (rd%failed()) return
        if (allow_inertial .and. (s == 'R' .or. s == 'INERTIAL')) then
            kb = 0
            return
        end if
        kb = findloc(bnames, s, dim=1)
        if (kb == 0) then
            call rd%fail(rd%context(i, f, what)//': found "'//trim(s)//'"; expected a body defined '// &
                         'on a BODY card'//merge(' or R', '     ', allow_inertial))
            kb = 1
        end if
    end function body_ref

    !> Coordinate named in field f: TX TY TZ RX RY RZ -> 1..6.
    integer function coord_ref(rd, i, f) result(m)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        integer, intent(in) :: f  !! the field (F1 .. F7)
        character(len=10) :: s
        m = 1
        call rd%name(i, f, 'coordinate', s)
        if (rd%failed()) return
        m = findloc(coord_names, s(1:2), dim=1)
        if (m == 0 .or. len_trim(s) /= 2) then
            call rd%fail(rd%context(i, f, 'coordinate')//': found "'//trim(s)//'"; expected TX TY TZ RX RY or RZ')
            m = 1
        end if
    end function coord_ref

    !> Table named in field f.
    integer function table_ref(rd, i, f, tabs) result(it)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        integer, intent(in) :: f  !! the field (F1 .. F7)
        type(named_table_t), intent(in) :: tabs(:)  !! the deck's named tables (TABLE, PULSE)
        character(len=10) :: s
        integer :: k
        it = 1
        call rd%name(i, f, 'table', s)
        if (rd%failed()) return
        it = 0
        do k = 1, size(tabs)
            if (tabs(k)%name == s) it = k
        end do
        if (it == 0) then
            call rd%fail(rd%context(i, f, 'table')//': found "'//trim(s)//'"; expected the name of a TABLE or PULSE card')
            it = 1
        end if
    end function table_ref

    !> An error: card i addresses coordinate m of deck body kold, which a LOCK
    !! or SCENE card locked (named with its location).
    subroutine locked_error(rd, i, bnames, bmap, kold, m)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        integer, intent(in) :: kold  !! the body in deck order
        integer, intent(in) :: m  !! the coordinate (1 .. 6: TX TY TZ RX RY RZ)
        character(len=10), intent(in) :: bnames(:)  !! the names of the deck's bodies, in deck order
        type(body_map_t), intent(in) :: bmap  !! where each deck body went (MERGE), what locked its coordinates
        character(len=:), allocatable :: by
        by = ' (LOCK or SCENE card)'
        if (bmap%locked_by(m, kold) > 0) by = ' by the '//trim(rd%key(bmap%locked_by(m, kold)))//' card at '// &
                                             rd%where(bmap%locked_by(m, kold))
        call rd%fail(rd%context(i, 2, 'coordinate')//': '//trim(bnames(kold))//'.'//coord_names(m)// &
                     ' is locked'//by//'; expected an active coordinate, or the neutral value')
    end subroutine locked_error

    !> Body (in the reduced tree) and coordinate of a card whose fields F1,
    !! F2 name a body and one of its coordinates (INITIAL, PRESCRIB, LIMIT,
    !! ...). A body absorbed by MERGE has no coordinates: an error, or with
    !! `merged` present merged = .true. and j = 0 (an element card dropped). A
    !! locked coordinate gives j = 0 when allow_locked, else an error.
    subroutine active_coordinate(rd, i, tree, bnames, bmap, kb, m, j, allow_locked, merged)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        type(body_tree_t), intent(in) :: tree  !! the reduced tree (its coordinate numbers)
        character(len=10), intent(in) :: bnames(:)  !! the names of the deck's bodies, in deck order
        type(body_map_t), intent(in) :: bmap  !! where each deck body went (MERGE), what locked its coordinates
        integer, intent(out) :: kb  !! the body in the reduced tree
        integer, intent(out) :: m  !! the coordinate (1 .. 6: TX TY TZ RX RY RZ)
        integer, intent(out) :: j  !! the model coordinate (0: a locked one)
        logical, intent(in) :: allow_locked  !! a locked coordinate gives j = 0 (otherwise an error)
        logical, intent(out), optional :: merged  !! the body was absorbed by MERGE (then no error; m, j = 0)
        integer :: kold
        j = 0
        kb = 1
        m = 0
        kold = body_ref(rd, i, 1, 'body', bnames, .false.)
        if (present(merged)) then
            merged = .false.
            if (rd%failed()) return
            merged = bmap%merged_by(kold) > 0
            if (merged) return
        end if
        m = coord_ref(rd, i, 2)
        if (rd%failed()) return
        if (bmap%merged_by(kold) > 0) then
            call rd%fail(rd%context(i, 1, 'body')//': body '//trim(bnames(kold))//' was merged by the MERGE card at '// &
                         rd%where(bmap%merged_by(kold))//'; its coordinates no longer exist')
            return
        end if
        kb = bmap%new(kold)
        j = tree%dof_index(m, kb)
        if (j == 0 .and. .not. allow_locked) call locked_error(rd, i, bnames, bmap, kold, m)
    end subroutine active_coordinate

    !> Deck unit of coordinate m and its factor to SI.
    pure function unit_of(m) result(u)
        integer, intent(in) :: m  !! the coordinate (1 .. 6: TX TY TZ RX RY RZ)
        character(len=3) :: u
        u = merge('m  ', 'deg', m <= 3)
    end function unit_of

    pure real(wp) function unit_factor(m) result(f)
        integer, intent(in) :: m  !! the coordinate (1 .. 6: TX TY TZ RX RY RZ)
        f = merge(one, deg, m <= 3)
    end function unit_factor

    !> Largest magnitude accepted for a coordinate value in deck units.
    pure real(wp) function unit_limit(m) result(f)
        integer, intent(in) :: m  !! the coordinate (1 .. 6: TX TY TZ RX RY RZ)
        f = merge(big_length, 3600.0_wp, m <= 3)
    end function unit_limit

    !> Error unless the two ends of an element (fields F2, F3) are on different bodies.
    subroutine distinct_bodies(rd, i, ka, kb)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's first deck line
        integer, intent(in) :: ka  !! body of end a (deck order; 0: R)
        integer, intent(in) :: kb  !! body of end b (deck order; 0: R)
        if (rd%failed()) return
        if (ka == kb) call rd%fail(rd%where(i)//', columns 21-40 ('//trim(rd%key(i))//' card, fields F2-F3): '// &
                                   'both ends on the same body; expected two different bodies')
    end subroutine distinct_bodies

    !> Old body numbers and points -> reduced tree (MERGE); counts the
    !! elements with both ends on one merged body.
    pure subroutine map_ends(bmap, ka, pa, kb, pb, ninternal)
        type(body_map_t), intent(in) :: bmap  !! where each deck body went (MERGE)
        integer, intent(inout) :: ka  !! body of end a: deck order in, reduced tree out (0: R)
        real(wp), intent(inout) :: pa(3)  !! point a in its body's frame, moved onto the merged body [m]
        integer, intent(inout) :: kb  !! body of end b: deck order in, reduced tree out (0: R)
        real(wp), intent(inout) :: pb(3)  !! point b in its body's frame, moved onto the merged body [m]
        integer, intent(inout) :: ninternal  !! elements so far with both ends on one merged body
        if (ka > 0) then
            pa = bmap%length*(pa + bmap%shift(:, ka))
            ka = bmap%new(ka)
        end if
        if (kb > 0) then
            pb = bmap%length*(pb + bmap%shift(:, kb))
            kb = bmap%new(kb)
        end if
        if (ka == kb) ninternal = ninternal + 1
    end subroutine map_ends

    !> Attachment points on a continuation card: F1-F3 on body a, F4-F6 on body b.
    subroutine line_points(rd, i, pa, pb)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the continuation card's deck line
        real(wp), intent(out) :: pa(3)  !! the point on body a [m]
        real(wp), intent(out) :: pb(3)  !! the point on body b [m]
        integer :: f
        do f = 1, 3
            call rd%real(i, f, 'point on body a', 'm', pa(f), -big_length, big_length)
            call rd%real(i, 3 + f, 'point on body b', 'm', pb(f), -big_length, big_length)
        end do
    end subroutine line_points

    !> The attachment of a LIGAMENT, MUSCLE or SPRING card: name (F1),
    !! bodies (F2, F3), points (first continuation card, F1-F6) and free
    !! length (line ll, field lf; blank: the neutral length), moved onto
    !! merged bodies; keep is false for an element inside one merged body.
    subroutine line_card(rd, ctx, i, what, at, ll, lf, keep)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_context_t), intent(inout) :: ctx  !! bodies and where each went; out: ninternal counted
        integer, intent(in) :: i  !! the card's first deck line
        character(len=*), intent(in) :: what  !! ligament, muscle or spring (messages, the free length's name)
        type(line_attach_t), intent(inout) :: at  !! the attachment
        integer, intent(in) :: ll  !! deck line of the free length
        integer, intent(in) :: lf  !! field of the free length
        logical, intent(out) :: keep  !! false for an element inside one merged body
        character(len=10) :: nm
        keep = .false.
        call rd%name(i, 1, what//' name', nm)
        at%name = nm
        at%body_a = body_ref(rd, i, 2, 'body a', ctx%bnames, .true.)
        at%body_b = body_ref(rd, i, 3, 'body b', ctx%bnames, .true.)
        call distinct_bodies(rd, i, at%body_a, at%body_b)
        call line_points(rd, i + 1, at%point_a, at%point_b)
        select case (what)
        case ('ligament')
            call rd%real(ll, lf, 'slack length', 'm', at%length0, 1.0e-6_wp, big_length, default=-one)
        case ('muscle')
            call rd%real(ll, lf, 'rest length', 'm', at%length0, 1.0e-6_wp, big_length, default=-one)
        case default
            call rd%real(ll, lf, 'free length', 'm', at%length0, zero, big_length, default=-one)
        end select
        if (rd%failed()) return
        if (at%length0 > zero) at%length0 = ctx%bmap%length*at%length0
        call map_ends(ctx%bmap, at%body_a, at%point_a, at%body_b, at%point_b, ctx%ninternal)
        keep = at%body_a /= at%body_b
    end subroutine line_card

end module hn_element_cards
