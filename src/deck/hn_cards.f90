!> The registry of deck cards: the one table of every card name, the
!! continuation cards it takes, the card group whose module reads it and
!! whether a deck may hold more than one of it. The deck reader's check of
!! card names (`card_known`), its grouping of continuation cards
!! (`card_ncont`) and its dispatch to the card groups (`deck_passes`) read
!! this table; docs/deck-format.md has one `### NAME`
!! section per card of it and of the family registry (test/scripts/deck_cards.sh).
!! The element families' cards are not in this table: they are the family
!! registry's (hn_families: name, continuation cards, one family each), in
!! the elements group, and may repeat.
!!
!! Adding a card: one line in `cards` and its handler in the module of its
!! group, called from that group's pass (docs/architecture.md, "Adding a
!! card").
module hn_cards
    use hn_families, only: card_continuations
    implicit none
    private

    public :: card_info_t, cards, card_index, card_known, card_ncont, card_group, card_repeats

    !> The card groups, each read by one module hn_deck_<group>.
    integer, parameter, public :: grp_control = 1, grp_bodies = 2, grp_scene = 3, grp_coordinates = 4, &
                                  grp_tables = 5, grp_elements = 6, grp_loads = 7, grp_changes = 8, ngroups = 8
    !> Their names (the module of group g is hn_deck_<group_name(g)>, lower case).
    character(len=11), parameter, public :: group_name(ngroups) = [character(len=11) :: 'CONTROL', 'BODIES', &
        'SCENE', 'COORDINATES', 'TABLES', 'ELEMENTS', 'LOADS', 'CHANGES']

    !> Continuation count of a card whose count is not fixed.
    integer, parameter, public :: ncont_computed = -1   !! computed from the card (TABLE: its points, or CSV)

    !> One card: its name, its continuation cards, its group, whether it may repeat.
    type :: card_info_t
        character(len=8) :: key = ''
        integer :: ncont = 0
        integer :: group = 0
        logical :: repeats = .true.
    end type card_info_t

    !> Every card of a deck (INCLUDE and END are the reader's, not cards).
    type(card_info_t), parameter :: cards(*) = [ &
        card_info_t('TITLE', 0, grp_control, .true.), &         ! an INCLUDEd deck's TITLE is a subtitle
        card_info_t('CONTROL', 0, grp_control, .false.), &
        card_info_t('SOLVER', 0, grp_control, .false.), &
        card_info_t('GRAVITY', 0, grp_control, .false.), &
        card_info_t('OUTPUT', 0, grp_control, .false.), &
        card_info_t('H5FILE', 0, grp_control, .false.), &
        card_info_t('EVENTS', 0, grp_control, .false.), &
        card_info_t('HOLD', 0, grp_control, .false.), &
        card_info_t('DUMP', 0, grp_control, .true.), &
        card_info_t('HEADNECK', 0, grp_control, .false.), &
        card_info_t('CRITERIA', 0, grp_control, .false.), &
        card_info_t('LOADCELL', 0, grp_control, .true.), &
        card_info_t('PRINT', 0, grp_control, .true.), &
        card_info_t('RUNLIMIT', 0, grp_control, .false.), &
        card_info_t('STATICS', 0, grp_control, .false.), &
        card_info_t('BODY', 0, grp_bodies, .true.), &
        card_info_t('BODYPI', 0, grp_bodies, .true.), &
        card_info_t('JOINT', 0, grp_bodies, .true.), &
        card_info_t('OCCUPANT', 0, grp_bodies, .false.), &
        card_info_t('SCENE', 0, grp_scene, .false.), &
        card_info_t('MERGE', 0, grp_scene, .true.), &
        card_info_t('LOCK', 0, grp_coordinates, .true.), &
        card_info_t('NEUTRAL', 0, grp_coordinates, .true.), &
        card_info_t('INITIAL', 0, grp_coordinates, .true.), &
        card_info_t('PRESCRIB', 0, grp_coordinates, .true.), &
        card_info_t('TABLE', ncont_computed, grp_tables, .true.), &
        card_info_t('PULSE', 0, grp_tables, .true.), &
        card_info_t('SCALE', 0, grp_elements, .true.), &
        card_info_t('FAMILY', 0, grp_elements, .true.), &
        card_info_t('FORCE', 1, grp_loads, .true.), &
        card_info_t('COUPLE', 0, grp_loads, .true.), &
        card_info_t('STIFFEN', 0, grp_loads, .true.), &
        card_info_t('CHANGE', 0, grp_changes, .true.)]

    !> One pass of the deck reader over the cards: the group whose module
    !! reads it and the handler of that module that does.
    type, public :: deck_pass_t
        integer :: group = 0
        character(len=16) :: handler = ''
    end type deck_pass_t

    !> The passes, in the order the cards depend on each other: the bodies
    !! (with the coordinates locked and the scene, which the tree needs), the
    !! control cards, the tables, the coordinates' motions (tables), the
    !! elements (the tree, the tables), the loads, the reported bodies, the
    !! stiffness factors (the elements), the model's CHANGE cards (the whole
    !! model) and RUNLIMIT. CHANGE cards rewrite fields before the first pass.
    type(deck_pass_t), parameter, public :: deck_passes(*) = [ &
        deck_pass_t(grp_bodies, 'body_cards'), &
        deck_pass_t(grp_control, 'control_cards'), &
        deck_pass_t(grp_tables, 'table_cards'), &
        deck_pass_t(grp_coordinates, 'coordinate_cards'), &
        deck_pass_t(grp_elements, 'element_cards'), &
        deck_pass_t(grp_loads, 'load_cards'), &
        deck_pass_t(grp_control, 'report_cards'), &
        deck_pass_t(grp_loads, 'stiffen_cards'), &
        deck_pass_t(grp_changes, 'model_changes'), &
        deck_pass_t(grp_control, 'runlimit_card')]

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

    !> Whether a deck may hold more than one card `key`.
    pure logical function card_repeats(key) result(yes)
        character(len=*), intent(in) :: key     !! card name (upper case)
        integer :: k
        k = card_index(key)
        if (k > 0) then
            yes = cards(k)%repeats
        else
            yes = card_continuations(key) >= 0
        end if
    end function card_repeats

end module hn_cards
