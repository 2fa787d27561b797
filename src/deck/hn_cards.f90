!> The registry of the case deck's cards: the one table of every card
!! name, the continuation cards it takes, the card group whose module reads
!! it and how many of it a deck may hold. The card engine (hn_card_engine)
!! reads the deck's format from this table (`case_deck_format`): its check
!! of card names, its grouping of continuation cards and its refusal of a
!! card given more often than its line allows; the passes of the card
!! groups (hn_deck_passes) read the cards. docs/deck-format.md has one
!! `### NAME` section per card of it and of the family registry
!! (test/scripts/deck_cards.sh). The element families' cards are not in
!! this table: they are the family registry's (hn_families: name,
!! continuation cards, one family each), in the elements group, and may
!! repeat (their repeats refused by their own rule, hn_deck).
!!
!! Adding a card: one line in `cards` and its handler in the module of its
!! group, called from that group's pass (docs/architecture.md, "Adding a
!! card").
module hn_cards
    use hn_deck_reader, only: deck_reader_t, upper
    use hn_card_engine, only: deck_format_t, deck_card_t, ncont_counted, any_times, at_most_once, exactly_once, &
                              once_per_file
    use hn_element_cards, only: family_card_t
    use hn_families, only: card_continuations, family_cards
    implicit none
    private

    public :: card_info_t, cards, card_index, card_known, card_ncont, card_group, card_repeats, case_deck_format
    public :: any_times, at_most_once, exactly_once, once_per_file

    !> The card groups, each read by one module hn_deck_<group>.
    integer, parameter, public :: grp_control = 1, grp_bodies = 2, grp_scene = 3, grp_coordinates = 4, &
                                  grp_tables = 5, grp_elements = 6, grp_loads = 7, grp_changes = 8, ngroups = 8
    !> Their names (the module of group g is hn_deck_<group_name(g)>, lower case).
    character(len=11), parameter, public :: group_name(ngroups) = [character(len=11) :: 'CONTROL', 'BODIES', &
        'SCENE', 'COORDINATES', 'TABLES', 'ELEMENTS', 'LOADS', 'CHANGES']

    !> Continuation count of a card whose count is not fixed: computed from
    !! the card (TABLE: its points, or CSV; `table_continuations`).
    integer, parameter, public :: ncont_computed = ncont_counted
    integer, parameter, public :: max_table_points = 100000 !! points of one TABLE

    !> One card: its name, its continuation cards, its group, how many of
    !! it a deck may hold (any_times, at_most_once, exactly_once,
    !! once_per_file: hn_card_engine).
    type :: card_info_t
        character(len=8) :: key = ''
        integer :: ncont = 0
        integer :: group = 0
        integer :: times = any_times
    end type card_info_t

    !> Every card of a deck (INCLUDE and END are the reader's, not cards).
    type(card_info_t), parameter :: cards(*) = [ &
        card_info_t('TITLE', 0, grp_control, once_per_file), &   ! an INCLUDEd deck's TITLE is a subtitle
        card_info_t('CONTROL', 0, grp_control, exactly_once), &
        card_info_t('SOLVER', 0, grp_control, at_most_once), &
        card_info_t('GRAVITY', 0, grp_control, at_most_once), &
        card_info_t('OUTPUT', 0, grp_control, at_most_once), &
        card_info_t('H5FILE', 0, grp_control, once_per_file), &  ! the deck's own wins over an INCLUDEd deck's
        card_info_t('EVENTS', 0, grp_control, at_most_once), &
        card_info_t('HOLD', 0, grp_control, at_most_once), &
        card_info_t('DUMP', 0, grp_control, any_times), &
        card_info_t('HEADNECK', 0, grp_control, at_most_once), &
        card_info_t('CRITERIA', 0, grp_control, at_most_once), &
        card_info_t('LOADCELL', 0, grp_control, any_times), &
        card_info_t('PRINT', 0, grp_control, any_times), &
        card_info_t('RUNLIMIT', 0, grp_control, at_most_once), &
        card_info_t('STATICS', 0, grp_control, at_most_once), &
        card_info_t('BODY', 0, grp_bodies, any_times), &
        card_info_t('BODYPI', 0, grp_bodies, any_times), &
        card_info_t('JOINT', 0, grp_bodies, any_times), &
        card_info_t('OCCUPANT', 0, grp_bodies, at_most_once), &
        card_info_t('SCENE', 0, grp_scene, at_most_once), &
        card_info_t('MERGE', 0, grp_scene, any_times), &
        card_info_t('LOCK', 0, grp_coordinates, any_times), &
        card_info_t('NEUTRAL', 0, grp_coordinates, any_times), &
        card_info_t('INITIAL', 0, grp_coordinates, any_times), &
        card_info_t('PRESCRIB', 0, grp_coordinates, any_times), &
        card_info_t('TABLE', ncont_computed, grp_tables, any_times), &
        card_info_t('PULSE', 0, grp_tables, any_times), &
        card_info_t('SCALE', 0, grp_elements, any_times), &
        card_info_t('FAMILY', 0, grp_elements, any_times), &
        card_info_t('FORCE', 1, grp_loads, any_times), &
        card_info_t('COUPLE', 0, grp_loads, any_times), &
        card_info_t('STIFFEN', 0, grp_loads, any_times), &
        card_info_t('CHANGE', 0, grp_changes, any_times)]

contains

    !> Place of card `key` in `cards`, 0 when it is no card.
    pure integer function card_index(key) result(k)
        character(len=*), intent(in) :: key     !! card name (upper case)
        do k = 1, size(cards)
            if (cards(k)%key == key) return
        end do
        k = 0
    end function card_index

    !> Whether `key` names a card (of this table or of an element family).
    pure logical function card_known(key) result(yes)
        character(len=*), intent(in) :: key     !! card name (upper case)
        yes = card_index(key) > 0
        if (.not. yes) yes = card_continuations(key) /= -1
    end function card_known

    !> Continuation cards card `key` takes (ncont_computed: TABLE; ncont_optional:
    !! one when the next line continues it; 0 when it is no card).
    pure integer function card_ncont(key) result(n)
        character(len=*), intent(in) :: key     !! card name (upper case)
        integer :: k
        k = card_index(key)
        if (k > 0) then
            n = cards(k)%ncont
        else
            n = card_continuations(key)
            if (n == -1) n = 0
        end if
    end function card_ncont

    !> Group of card `key` (grp_control ... grp_changes; 0 when it is no card).
    pure integer function card_group(key) result(g)
        character(len=*), intent(in) :: key     !! card name (upper case)
        integer :: k
        k = card_index(key)
        if (k > 0) then
            g = cards(k)%group
        else
            g = merge(grp_elements, 0, card_continuations(key) >= 0)
        end if
    end function card_group

    !> Whether a deck may hold more than one card `key` (TITLE and H5FILE:
    !! one in each of its files).
    pure logical function card_repeats(key) result(yes)
        character(len=*), intent(in) :: key     !! card name (upper case)
        integer :: k
        k = card_index(key)
        if (k > 0) then
            yes = cards(k)%times == any_times .or. cards(k)%times == once_per_file
        else
            yes = card_continuations(key) >= 0
        end if
    end function card_repeats

    !> The case deck's format for the card engine: the cards of `cards`,
    !! then the element families' cards `fc` (default: the registry's,
    !! family_cards; any number of each, their repeats refused by their own
    !! rule in hn_deck). No card has a handler: the passes of the card
    !! groups read them (hn_deck_passes).
    function case_deck_format(fc) result(fmt)
        type(family_card_t), intent(in), optional :: fc(:)   !! the deck's family cards (registry and others)
        type(deck_format_t) :: fmt
        type(family_card_t), allocatable :: more(:)
        integer :: k
        if (present(fc)) then
            more = fc
        else
            more = family_cards()
        end if
        fmt%name = 'case deck'
        fmt%doc = 'docs/deck-format.md'
        allocate (fmt%cards(size(cards) + size(more)))
        do k = 1, size(cards)
            fmt%cards(k) = deck_card_t(cards(k)%key, cards(k)%ncont, cards(k)%times, null())
            if (cards(k)%ncont == ncont_computed) fmt%cards(k)%count => table_continuations
        end do
        do k = 1, size(more)
            fmt%cards(size(cards) + k) = deck_card_t(more(k)%key, more(k)%ncont, any_times, null())
        end do
    end function case_deck_format

    !> The continuation cards of a TABLE card at deck line i: its points
    !! (F2) three to a card, or one card naming its CSV file (F5 CSV).
    subroutine table_continuations(rd, i, n)
        type(deck_reader_t), intent(inout) :: rd   !! the deck; a located error on a bad point count
        integer, intent(in) :: i                   !! the TABLE card's deck line
        integer, intent(out) :: n                  !! its continuation cards
        character(len=10) :: s
        integer :: ios, npts
        n = 0
        s = rd%raw(i, 2)
        read (s, *, iostat=ios) npts
        if (ios /= 0 .or. npts < 1 .or. npts > max_table_points) then
            call rd%int(i, 2, 'number of points', npts, 1, max_table_points)
            if (.not. rd%failed()) call rd%fail(rd%where(i)//': bad TABLE point count')
            return
        end if
        n = (npts + 2)/3
        if (upper(adjustl(rd%raw(i, 5))) == 'CSV') n = 1     ! the file name card
    end subroutine table_continuations

end module hn_cards
