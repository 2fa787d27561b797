!> The passes of the case deck's reader over its cards, in the order the
!! cards depend on each other. Each pass is a procedure of the interface
!! `deck_pass` that reads the cards of one card group (its module
!! hn_deck_<group>, hn_cards' group of each card) into the case, on the
!! reading state the passes share (`deck_reading_t`); `deck_passes` is the
!! table of them, so a pass whose procedure is missing or takes other
!! arguments does not compile. hn_deck runs them in turn.
module hn_deck_passes
    use hn_case, only: case_t
    use hn_deck_reader, only: deck_reader_t
    use hn_model, only: model_add_family
    use hn_element_family, only: family_slot_t
    use hn_families, only: family_registration_t
    use hn_changes, only: change_t, apply_model_changes
    use hn_cards, only: grp_control, grp_bodies, grp_tables, grp_coordinates, grp_elements, grp_loads, grp_changes
    use hn_occupant, only: occupant_bodies, occupant_elements
    use hn_deck_state, only: deck_state_t
    use hn_deck_control, only: runlimit_card, control_cards, report_cards
    use hn_deck_coordinates, only: coordinate_cards
    use hn_deck_bodies, only: body_cards
    use hn_deck_tables, only: table_cards
    use hn_deck_elements, only: element_cards
    use hn_deck_loads, only: load_cards, stiffen_cards
    implicit none
    private

    public :: deck_pass, deck_passes

    !> What the passes over a case deck share besides the reader and the
    !! case: the card groups' state (the cards, the bodies, the tables, the
    !! family cards), the CHANGE cards read before the first pass, and the
    !! element families a program brings that the registry does not list.
    type, public :: deck_reading_t
        type(deck_state_t) :: st                                   !! the card groups' state
        type(change_t), allocatable :: changes(:)                  !! the CHANGE cards (field changes already made)
        type(family_registration_t), allocatable :: families(:)    !! families outside the registry
    end type deck_reading_t

    abstract interface
        !> One pass: the cards of its group into the case.
        subroutine deck_pass(rd, dr, cs)
            import :: deck_reader_t, deck_reading_t, case_t
            type(deck_reader_t), intent(inout) :: rd    !! the deck: card images, located field access, the first error
            type(deck_reading_t), intent(inout) :: dr   !! what the passes share
            type(case_t), intent(inout) :: cs           !! the run case the cards fill
        end subroutine deck_pass
    end interface

    !> One pass: the group it reads and the procedure that reads it.
    type, public :: deck_pass_t
        integer :: group = 0                              !! its card group (hn_cards)
        procedure(deck_pass), pointer, nopass :: read     !! the procedure (no default: the table names it)
    end type deck_pass_t

contains

    !> The passes, in the order the cards depend on each other: the bodies
    !! (with the coordinates locked and the scene, which the tree needs), the
    !! control cards, the tables, the coordinates' motions (tables), the
    !! elements (the tree, the tables), the loads, the reported bodies, the
    !! stiffness factors (the elements), the model's CHANGE cards (the whole
    !! model) and RUNLIMIT. CHANGE cards rewrite fields before the first pass.
    function deck_passes() result(p)
        type(deck_pass_t), allocatable :: p(:)   !! the passes in order
        p = [deck_pass_t(grp_bodies, bodies_pass), &
             deck_pass_t(grp_control, control_pass), &
             deck_pass_t(grp_tables, tables_pass), &
             deck_pass_t(grp_coordinates, coordinates_pass), &
             deck_pass_t(grp_elements, elements_pass), &
             deck_pass_t(grp_loads, loads_pass), &
             deck_pass_t(grp_control, report_pass), &
             deck_pass_t(grp_loads, stiffen_pass), &
             deck_pass_t(grp_changes, changes_pass), &
             deck_pass_t(grp_control, runlimit_pass)]
    end function deck_passes

    !> The bodies (the tree, MERGE and SCENE, OCCUPANT), then the families
    !! outside the registry join the model after the registry's.
    subroutine bodies_pass(rd, dr, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_reading_t), intent(inout) :: dr
        type(case_t), intent(inout) :: cs
        type(family_slot_t) :: slot
        integer :: k, f
        call body_cards(rd, dr%st%cards, cs, dr%st%bnames, dr%st%bmap)
        if (.not. rd%failed()) call occupant_bodies(rd, dr%st%cards, cs, dr%st%bmap)
        if (rd%failed()) return
        do k = 1, size(dr%families)
            call dr%families(k)%empty(slot)
            call model_add_family(cs%model, slot%f, f)
        end do
    end subroutine bodies_pass

    !> TITLE and the run-control cards.
    subroutine control_pass(rd, dr, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_reading_t), intent(inout) :: dr
        type(case_t), intent(inout) :: cs
        call control_cards(rd, dr%st%cards, cs)
    end subroutine control_pass

    !> TABLE and PULSE.
    subroutine tables_pass(rd, dr, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_reading_t), intent(inout) :: dr
        type(case_t), intent(inout) :: cs
        call table_cards(rd, dr%st%cards, dr%st%tabs, cs)
    end subroutine tables_pass

    !> NEUTRAL, INITIAL, PRESCRIB (LOCK: with the bodies).
    subroutine coordinates_pass(rd, dr, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_reading_t), intent(inout) :: dr
        type(case_t), intent(inout) :: cs
        call coordinate_cards(rd, dr%st, cs)
    end subroutine coordinates_pass

    !> The element families' cards, SCALE and FAMILY.
    subroutine elements_pass(rd, dr, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_reading_t), intent(inout) :: dr
        type(case_t), intent(inout) :: cs
        call element_cards(rd, dr%st, cs)
    end subroutine elements_pass

    !> FORCE and COUPLE.
    subroutine loads_pass(rd, dr, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_reading_t), intent(inout) :: dr
        type(case_t), intent(inout) :: cs
        call load_cards(rd, dr%st, cs)
    end subroutine loads_pass

    !> HEADNECK, CRITERIA, LOADCELL, PRINT and STATICS (the bodies read).
    subroutine report_pass(rd, dr, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_reading_t), intent(inout) :: dr
        type(case_t), intent(inout) :: cs
        call report_cards(rd, dr%st%cards, cs, dr%st%bnames, dr%st%bmap)
    end subroutine report_pass

    !> STIFFEN (the elements read).
    subroutine stiffen_pass(rd, dr, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_reading_t), intent(inout) :: dr
        type(case_t), intent(inout) :: cs
        call stiffen_cards(rd, dr%st%cards, cs)
    end subroutine stiffen_pass

    !> OCCUPANT's scaling of the elements, then the CHANGE cards of the model
    !! (FAMILY and BODY kinds: the whole model read).
    subroutine changes_pass(rd, dr, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_reading_t), intent(inout) :: dr
        type(case_t), intent(inout) :: cs
        call occupant_elements(rd, dr%st%cards, cs)
        if (.not. rd%failed()) call apply_model_changes(rd, dr%changes, cs%model, cs%changes)
    end subroutine changes_pass

    !> RUNLIMIT.
    subroutine runlimit_pass(rd, dr, cs)
        type(deck_reader_t), intent(inout) :: rd
        type(deck_reading_t), intent(inout) :: dr
        type(case_t), intent(inout) :: cs
        call runlimit_card(rd, dr%st%cards, cs)
    end subroutine runlimit_pass

end module hn_deck_passes
