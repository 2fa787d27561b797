!> What every element family does, behind one abstract type: a family
!! (discs, ligaments, ...) holds its typed elements in a concrete type that
!! extends `element_family_t` and implements every deferred binding; the
!! model holds one slot per family (`family_slot_t`) and calls each binding
!! once per family, never per element, so the typed inner loops stay inside
!! the family. A family that leaves a binding out does not compile.
!!
!! The bindings: size and outputs (`count`, `ncomp`), the neutral set-up
!! (`set_neutral`), the loads at one instant (`add_loads`), the tangent of
!! the loads for the structured Jacobian (`add_tangent`), the switching
!! functions of one-way elements (`switch_count`, `switching`), the channel
!! definitions (`channels`; the values are the family's outputs), the
!! result-file table (`result_table`), the plausibility warnings
!! (`plausibility`) and the properties that SCALE, CHANGE ... FAMILY, the
!! sweeps' FAMILY parameters and STIFFEN scale (`scale_items`, `scale`,
!! `stiffen`); and reading its own deck cards (`read_card`, one card into
!! its elements; `end_cards`, what follows when every card is read), with
!! the cards of a family the registry does not list (`deck_cards`). These
!! three have defaults: no card, nothing after the cards.
!!
!! What the run and the studies ask of a family, with defaults (none): the
!! input tables whose corners the run's steps land on (`input_tables`), the
!! times its controllers sample (`control_times`, `control_update`), a
!! pre-strained neutral (`prestrain`), whether it is active muscle (what a
!! passive state switches off, `active_muscle`), and its run monitors:
!! quantities the run watches at every output time (`monitor_count`,
!! `monitor`: their excess beyond what the family allows), the listing
!! lines and the run's warning from their peaks (`monitor_report`), and a
!! warning on a settled start (`neutral_warning`).
!!
!! States of a family in the equations of motion, with defaults (none):
!! `state_count` of them, their values at the start (`state_start`) and
!! their rates (`state_rates`); the dynamics (hn_dynamics) carries them in
!! the state vector after the coordinates and rates, and gives a family
!! their current values (`set_state`, into the component `state`) before
!! its loads, tangent, switching functions or controllers are evaluated.
!! `state` is unallocated where no state vector exists (the statics, a
!! model outside a run): a family then uses its states' start values or
!! an equivalent closed form.
module hn_element_family
    use hn_kinds, only: wp, zero
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t
    use hn_tree, only: body_tree_t
    use hn_rotation, only: cross
    use hn_line_elements, only: line_geometry_t, line_geometry, max_via
    use hn_deck_reader, only: deck_reader_t
    use hn_element_cards, only: card_context_t, family_card_t
    use hn_tables, only: table_t
    implicit none
    private

    public :: element_family_t, family_slot_t, family_channel_t, element_table_t, table_data_t, family_work_t
    public :: family_energy_t, tangent_work_t, tangent_work
    public :: path_columns, spatial_row, item_channels
    public :: add_warning, check_point, check_range, line_columns, add_line_tangent

    integer, parameter, public :: max_family_items = 12  !! most properties a family has to scale
    integer, parameter, public :: item_len = 10           !! length of a property name
    integer, parameter, public :: warning_len = 160       !! length of a plausibility warning

    !> Relative step of the central differences of the element laws in the
    !! tangents, and the smallest absolute steps [m, m/s, rad, rad/s] (laws
    !! are smooth on that scale; a kink inside the interval gives the mean slope).
    real(wp), parameter, public :: fd_rel = 1.0e-6_wp
    real(wp), parameter, public :: fd_abs_length = 1.0e-9_wp, fd_abs_rate = 1.0e-6_wp

    !> Scratch of a family's loads kept between evaluations (sized once,
    !! by element_output_allocate): the line elements' geometry.
    type :: family_work_t
        type(line_geometry_t), allocatable :: g(:)        !! (count) geometry of each line element
        type(line_geometry_t), allocatable :: seg(:, :)   !! (max_via + 1, count) segments of muscle paths
    end type family_work_t

    !> What a family's elements store and spend at one instant, each family's
    !! share added by its `add_loads` (the run's energy balance).
    type :: family_energy_t
        real(wp) :: u_elastic = zero   !! energy stored in the elements [J]
        real(wp) :: p_diss = zero      !! power dissipated by them [W]
        real(wp) :: p_muscle = zero    !! power absorbed by the muscles [W]
    end type family_energy_t

    !> Scratch of the families' tangents for n active coordinates, sized once
    !! per Jacobian (tangent_work): an element's row b = dL/dxdot of its
    !! length, the joint columns it spans and their signs (line_columns), the
    !! nonzero entries of b, and the 6 x n spatial rows of a joint element.
    type :: tangent_work_t
        integer, allocatable :: cols(:)       !! (n) columns an element's row spans
        integer, allocatable :: sgn(:)        !! (n) their signs
        integer, allocatable :: idx(:)        !! (n) nonzero entries of b
        real(wp), allocatable :: b(:)         !! (n) the element's row
        real(wp), allocatable :: bd(:, :)     !! (6, n) a joint element's spatial rows
    end type tangent_work_t

    !> One channel a family defines: its value is output (comp, item) of the family.
    type :: family_channel_t
        character(len=24) :: name = ''
        character(len=12) :: units = ''
        character(len=16) :: group = ''
        integer :: item = 0     !! element number in the family
        integer :: comp = 0     !! row of the family's output array
    end type family_channel_t

    !> One extra dataset of a family's result table (below its group).
    type :: table_data_t
        character(len=24) :: name = ''            !! dataset name in the group
        character(len=16) :: units = ''
        character(len=200) :: description = ''
        real(wp), allocatable :: r(:)             !! real values (flat, Fortran order), or
        integer, allocatable :: i(:)              !! integer values
        integer, allocatable :: shape(:)          !! their shape
    end type table_data_t

    !> A family's table in the result file: group /model/elements/GROUP with
    !! names, body pairs and attachment points, and extra datasets.
    type :: element_table_t
        character(len=16) :: group = ''           !! '' : the family has no table
        character(len=200) :: description = ''
        character(len=12), allocatable :: name(:) !! (ne) element names
        integer, allocatable :: body(:, :)        !! (2, ne) bodies a, b (0 = R)
        real(wp), allocatable :: point(:, :, :)   !! (3, 2, ne) points a, b in body frames [m]
        type(table_data_t), allocatable :: extra(:)
    end type element_table_t

    !> An element family: its elements (in the extending type) and what it does.
    type, abstract :: element_family_t
        real(wp), allocatable :: state(:)   !! (state_count) the family's states now (unallocated: none given)
    contains
        procedure(count_fn), deferred :: count
        procedure(count_fn), deferred :: ncomp
        procedure(neutral_sub), deferred :: set_neutral
        procedure(loads_sub), deferred :: add_loads
        procedure(tangent_sub), deferred :: add_tangent
        procedure(count_fn), deferred :: switch_count
        procedure(switching_sub), deferred :: switching
        procedure(channels_fn), deferred :: channels
        procedure(table_fn), deferred :: result_table
        procedure(plausibility_sub), deferred :: plausibility
        procedure(items_sub), deferred :: scale_items
        procedure(scale_sub), deferred :: scale
        procedure(stiffen_sub), deferred :: stiffen
        procedure :: read_card => no_card
        procedure :: end_cards => nothing_after_cards
        procedure :: deck_cards => registry_cards
        procedure :: prestrain => no_prestrain
        procedure :: control_times => no_control_times
        procedure :: control_update => no_control_update
        procedure :: input_tables => no_input_tables
        procedure :: active_muscle => not_active_muscle
        procedure :: monitor_count => no_monitor_count
        procedure :: monitor => no_monitor
        procedure :: monitor_report => no_monitor_report
        procedure :: neutral_warning => no_neutral_warning
        procedure :: state_count => no_state_count
        procedure :: state_start => no_state_start
        procedure :: state_rates => no_state_rates
        procedure, non_overridable :: set_state => family_set_state
    end type element_family_t

    !> One slot of the model: a family of any kind.
    type :: family_slot_t
        class(element_family_t), allocatable :: f
    end type family_slot_t

    abstract interface
        !> A count: elements, output rows or switching functions of the family.
        pure integer function count_fn(this) result(n)
            import :: element_family_t
            class(element_family_t), intent(in) :: this   !! the family
        end function count_fn

        !> Set up the neutral configuration from its kinematics.
        pure subroutine neutral_sub(this, kin)
            import :: element_family_t, kinematics_t
            class(element_family_t), intent(inout) :: this   !! the family; out: references set
            type(kinematics_t), intent(in) :: kin            !! kinematics of the neutral configuration
        end subroutine neutral_sub

        !> Add the family's loads at time t to the body loads and generalized forces.
        pure subroutine loads_sub(this, t, kin, x, xd, loads, out, work, energy)
            import :: element_family_t, kinematics_t, body_loads_t, wp, family_work_t, family_energy_t
            class(element_family_t), intent(in) :: this      !! the family
            real(wp), intent(in) :: t                        !! time [s]
            type(kinematics_t), intent(in) :: kin            !! kinematics at (x, xd)
            real(wp), intent(in) :: x(:)                     !! active coordinates [m, rad]
            real(wp), intent(in) :: xd(:)                    !! their rates [m/s, rad/s]
            type(body_loads_t), intent(inout) :: loads       !! loads, the family's added
            real(wp), intent(inout) :: out(:, :)             !! (ncomp, count) the elements' outputs
            type(family_work_t), intent(inout) :: work       !! scratch sized for the family
            type(family_energy_t), intent(inout) :: energy   !! energy stored, power dissipated and absorbed, the family's added
        end subroutine loads_sub

        !> Add the family's generalized stiffness K and damping C.
        pure subroutine tangent_sub(this, tree, kin, t, x, xd, kgen, cgen, tw)
            import :: element_family_t, body_tree_t, kinematics_t, wp, tangent_work_t
            class(element_family_t), intent(in) :: this      !! the family
            type(body_tree_t), intent(in) :: tree            !! the body tree
            type(kinematics_t), intent(in) :: kin            !! kinematics of (x, xd): joint columns filled
            real(wp), intent(in) :: t                        !! time [s]
            real(wp), intent(in) :: x(:)                     !! active coordinates [m, rad]
            real(wp), intent(in) :: xd(:)                    !! their rates [m/s, rad/s]
            real(wp), intent(inout) :: kgen(:, :)            !! (n, n) generalized stiffness, the family's added
            real(wp), intent(inout) :: cgen(:, :)            !! (n, n) generalized damping, the family's added
            type(tangent_work_t), intent(inout) :: tw        !! scratch sized for the coordinates
        end subroutine tangent_sub

        !> The family's switching functions (whose sign changes mark where a one-way element switches).
        pure subroutine switching_sub(this, t, kin, x, sw)
            import :: element_family_t, kinematics_t, wp
            class(element_family_t), intent(in) :: this      !! the family
            real(wp), intent(in) :: t                        !! time [s]
            type(kinematics_t), intent(in) :: kin            !! kinematics at x
            real(wp), intent(in) :: x(:)                     !! active coordinates [m, rad]
            real(wp), intent(out) :: sw(:)                   !! (switch_count) the switching functions
        end subroutine switching_sub

        !> The family's output channels.
        pure function channels_fn(this, tree) result(c)
            import :: element_family_t, body_tree_t, family_channel_t
            class(element_family_t), intent(in) :: this      !! the family
            type(body_tree_t), intent(in) :: tree            !! the body tree (names)
            type(family_channel_t), allocatable :: c(:)
        end function channels_fn

        !> The family's table in the result file.
        pure function table_fn(this) result(tab)
            import :: element_family_t, element_table_t
            class(element_family_t), intent(in) :: this      !! the family
            type(element_table_t) :: tab
        end function table_fn

        !> Warnings about doubtful values of the family's elements, added to `warnings`.
        pure subroutine plausibility_sub(this, tree, warnings)
            import :: element_family_t, body_tree_t, warning_len
            class(element_family_t), intent(in) :: this      !! the family
            type(body_tree_t), intent(in) :: tree            !! the body tree
            character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, the family's added
        end subroutine plausibility_sub

        !> The properties that a FAMILY parameter may scale ('' after the last).
        pure subroutine items_sub(this, items)
            import :: element_family_t, max_family_items, item_len
            class(element_family_t), intent(in) :: this      !! the family
            character(len=item_len), intent(out) :: items(max_family_items)   !! the properties
        end subroutine items_sub

        !> Multiply one property of every element by `factor`.
        pure subroutine scale_sub(this, item, factor)
            import :: element_family_t, wp
            class(element_family_t), intent(inout) :: this   !! the family
            character(len=*), intent(in) :: item             !! property, one of scale_items()
            real(wp), intent(in) :: factor                   !! the factor
        end subroutine scale_sub

        !> STIFFEN: multiply the elements' stiffnesses by `factor`.
        pure subroutine stiffen_sub(this, factor)
            import :: element_family_t, wp
            class(element_family_t), intent(inout) :: this   !! the family
            real(wp), intent(in) :: factor                   !! the factor
        end subroutine stiffen_sub
    end interface

    real(wp), parameter :: far_factor = 100.0_wp   !! "two orders of magnitude" of a stiffness check

contains

    !> Read card `key` at deck line i into the family's elements (the
    !! default: a family with no cards refuses it). A family reads its cards
    !! into an empty family (new_family), in the order its registry entries
    !! say (card_first, card_in_order, card_last), with the field access of
    !! `rd` and the references of `ctx`.
    subroutine no_card(this, rd, ctx, i, key)
        class(element_family_t), intent(inout) :: this   !! the family; out: the card's element added
        type(deck_reader_t), intent(inout) :: rd         !! the deck: card images, located field access, the first error
        type(card_context_t), intent(inout) :: ctx       !! the deck's bodies, tables, tree; what the families report
        integer, intent(in) :: i                         !! the card's first deck line
        character(len=*), intent(in) :: key              !! the card name
        call rd%fail(rd%where(i)//' ('//trim(key)//' card): the element family of this card reads no cards')
    end subroutine no_card

    !> What follows when every card of the deck is read (the default: nothing).
    subroutine nothing_after_cards(this, rd, ctx)
        class(element_family_t), intent(inout) :: this   !! the family; out: its elements complete
        type(deck_reader_t), intent(inout) :: rd         !! the deck: card images, located field access, the first error
        type(card_context_t), intent(inout) :: ctx       !! the deck's cards; out: the family's scene notes added
    end subroutine nothing_after_cards

    !> Pre-strain the family's elastic neutral: its references measured in
    !! the configuration of `kin`, the neutral one with the active
    !! coordinates displaced by dx (HOLD PRESTRAIN, a settled start). The
    !! default: none (the family keeps its references: line elements their
    !! free lengths, range elements their ranges).
    pure subroutine no_prestrain(this, kin, dx)
        class(element_family_t), intent(inout) :: this   !! the family (unchanged)
        type(kinematics_t), intent(in) :: kin            !! kinematics of the displaced neutral (unused)
        real(wp), intent(in) :: dx(:)                    !! displacement of the active coordinates [m, rad] (unused)
    end subroutine no_prestrain

    !> The times in [t0, t1] at which the family's controllers sample the
    !! state (the run lands its steps there); the default: none.
    pure function no_control_times(this, t0, t1, tol) result(tk)
        class(element_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: t0                    !! start of the run [s]
        real(wp), intent(in) :: t1                    !! its end [s]
        real(wp), intent(in) :: tol                   !! time tolerance [s]
        real(wp), allocatable :: tk(:)
        allocate (tk(0))
    end function no_control_times

    !> The run has reached time t with kinematics kin (a control time, or
    !! its start): the family's controllers sample; the default: none.
    pure subroutine no_control_update(this, t, kin, tol)
        class(element_family_t), intent(inout) :: this   !! the family (unchanged)
        real(wp), intent(in) :: t                        !! time reached [s]
        type(kinematics_t), intent(in) :: kin            !! kinematics there (unused)
        real(wp), intent(in) :: tol                      !! time tolerance [s] (unused)
    end subroutine no_control_update

    !> The piecewise-linear input tables of the family, in time, whose
    !! corners the run's steps land on (hn_breakpoints); the default: none.
    pure function no_input_tables(this) result(tabs)
        class(element_family_t), intent(in) :: this   !! the family
        type(table_t), allocatable :: tabs(:)
        allocate (tabs(0))
    end function no_input_tables

    !> Whether the family is active muscle, which a passive state of the
    !! model (the calibration's PASSIVE) switches off; the default: no.
    pure logical function not_active_muscle(this) result(yes)
        class(element_family_t), intent(in) :: this   !! the family
        yes = .false.
    end function not_active_muscle

    !> Number of quantities the family's run monitor watches; the default: none.
    pure integer function no_monitor_count(this) result(n)
        class(element_family_t), intent(in) :: this   !! the family
        n = 0
    end function no_monitor_count

    !> The monitor's quantities at coordinates x: the excess of each beyond
    !! what the family allows (0 inside); the run keeps the peak of each and
    !! when it occurred. The default: none.
    pure subroutine no_monitor(this, x, excess)
        class(element_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: x(:)                  !! active coordinates [m, rad]
        real(wp), intent(out) :: excess(:)            !! (monitor_count) the excess of each (>= 0)
        excess = zero
    end subroutine no_monitor

    !> The monitor's report at the end of a run from the peaks of its
    !! quantities: lines for the listing and, when any, the run's one-line
    !! warning (blank: none). The default: nothing to report.
    pure subroutine no_monitor_report(this, peak, tpeak, lines, summary)
        class(element_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: peak(:)               !! (monitor_count) largest excess of each
        real(wp), intent(in) :: tpeak(:)              !! (monitor_count) when [s]
        character(len=warning_len), allocatable, intent(out) :: lines(:)   !! the listing's lines
        character(len=:), allocatable, intent(out) :: summary              !! the run's warning ('': none)
        allocate (lines(0))
        summary = ''
    end subroutine no_monitor_report

    !> A warning on a settled start (HOLD PRESTRAIN): the neutral xr
    !! displaced by dx, where the run starts; '' when none (the default).
    pure function no_neutral_warning(this, xr, dx) result(w)
        class(element_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: xr(:)                 !! neutral active coordinates [m, rad]
        real(wp), intent(in) :: dx(:)                 !! the settled displacement [m, rad]
        character(len=:), allocatable :: w
        w = ''
    end function no_neutral_warning

    !> Number of the family's states in the equations of motion; the default: none.
    pure integer function no_state_count(this) result(n)
        class(element_family_t), intent(in) :: this   !! the family
        n = 0
    end function no_state_count

    !> The family's states at the start of a run; the default: none.
    pure subroutine no_state_start(this, s)
        class(element_family_t), intent(in) :: this   !! the family
        real(wp), intent(out) :: s(:)                 !! (state_count) their start values
        s = zero
    end subroutine no_state_start

    !> The rates of the family's states s at time t and kinematics kin;
    !! the default: none.
    pure subroutine no_state_rates(this, t, kin, s, sdot)
        class(element_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics of the state (unused here)
        real(wp), intent(in) :: s(:)                  !! (state_count) the states
        real(wp), intent(out) :: sdot(:)              !! (state_count) their rates
        sdot = zero
    end subroutine no_state_rates

    !> Give the family the current values of its states (what its loads,
    !! tangent, switching functions and controllers see).
    pure subroutine family_set_state(this, s)
        class(element_family_t), intent(inout) :: this   !! the family; out: state = s
        real(wp), intent(in) :: s(:)                     !! (state_count) the states
        if (allocated(this%state)) then
            if (size(this%state) == size(s)) then
                this%state(:) = s
                return
            end if
            deallocate (this%state)
        end if
        allocate (this%state(size(s)))
        this%state(:) = s
    end subroutine family_set_state

    !> The cards of a family the registry (hn_families, family_cards) does
    !! not list, one added to a model in code (model_add_family) or brought
    !! to a deck (read_case's `families`), with their repeat rule and
    !! coordinate flag; the default: none (a registry family's cards are the
    !! registry's).
    pure function registry_cards(this) result(c)
        class(element_family_t), intent(in) :: this      !! the family
        type(family_card_t), allocatable :: c(:)
        allocate (c(0))
    end function registry_cards

    !> Warn of an attachment point farther from its body's mass centre than
    !! max(0.25 m, 5 radii of gyration).
    pure subroutine check_point(tree, k, p, what, warnings)
        type(body_tree_t), intent(in) :: tree    !! the body tree
        integer, intent(in) :: k                 !! the body (0 = R: not checked)
        real(wp), intent(in) :: p(3)             !! the point in the body frame [m]
        character(len=*), intent(in) :: what     !! the element, for the message
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, one added if far
        character(len=warning_len) :: w
        real(wp) :: reach
        if (k < 1) return
        reach = max(0.25_wp, 5*sqrt((tree%inertia(1, 1, k) + tree%inertia(2, 2, k) + &
                                     tree%inertia(3, 3, k))/(2*tree%mass(k))))
        if (norm2(p) > reach) then
            write (w, '(a,a,a,f7.3,a,f6.3,a)') trim(what), ': attachment on ', trim(tree%name(k)), &
                norm2(p), ' m from its mass centre, far outside the body (more than ', reach, ' m)'
            call add_warning(warnings, w)
        end if
    end subroutine check_point

    !> Warn of a positive value two or more orders of magnitude from the reference model's.
    pure subroutine check_range(what, v, ref, units, warnings)
        character(len=*), intent(in) :: what     !! the value, for the message
        real(wp), intent(in) :: v                !! the value
        real(wp), intent(in) :: ref              !! the reference model's
        character(len=*), intent(in) :: units    !! its units
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, one added if far
        character(len=warning_len) :: w
        if (v <= zero) return
        if (v > far_factor*ref .or. v < ref/far_factor) then
            write (w, '(2a,es10.3,3a,es9.2,a)') trim(what), ' = ', v, ' ', units, &
                ' is two or more orders of magnitude from the reference model''s ', ref, ' (check units)'
            call add_warning(warnings, w)
        end if
    end subroutine check_range

    !> A line element's deformation-rate row b_i = dL/dxdot_i = sj_i . phi_b
    !! - sj_i . phi_a with the spatial force phi = ((p - origin) x u; u) of a
    !! unit tension at each end, summed over the segments of its path
    !! (points in order: the two ends and a muscle's via points between),
    !! and its length and lengthening rate. ok is false for a segment of
    !! zero length (no tangent).
    pure subroutine line_columns(tree, kin, bodies, points, npt, cols, sgn, b, length, rate, ok)
        type(body_tree_t), intent(in) :: tree            !! the body tree
        type(kinematics_t), intent(in) :: kin            !! kinematics: joint columns filled
        integer, intent(in) :: bodies(max_via + 2)       !! bodies of the path's points
        real(wp), intent(in) :: points(3, max_via + 2)   !! the points in their body frames [m]
        integer, intent(in) :: npt                       !! number of points
        integer, intent(out) :: cols(:)                  !! scratch, at least n long
        integer, intent(out) :: sgn(:)                   !! scratch, at least n long
        real(wp), intent(out) :: b(:)                    !! (n) the row
        real(wp), intent(out) :: length                  !! path length [m]
        real(wp), intent(out) :: rate                    !! its rate [m/s]
        logical, intent(out) :: ok                       !! every segment has a length
        type(line_geometry_t) :: g
        integer :: k, ncol, i
        real(wp) :: phia(6), phib(6)
        b = zero; length = zero; rate = zero
        ok = .false.
        do k = 1, npt - 1
            call line_geometry(kin, bodies(k), points(:, k), bodies(k + 1), points(:, k + 1), g)
            if (g%length <= zero) return
            length = length + g%length
            rate = rate + g%rate
            phia = [cross(g%pa - kin%origin, g%unit), g%unit]
            phib = [cross(g%pb - kin%origin, g%unit), g%unit]
            call path_columns(tree, bodies(k), bodies(k + 1), cols, sgn, ncol)
            do i = 1, ncol
                if (sgn(i) > 0) then
                    b(cols(i)) = b(cols(i)) + dot_product(kin%sj(:, cols(i)), phib)
                else
                    b(cols(i)) = b(cols(i)) - dot_product(kin%sj(:, cols(i)), phia)
                end if
            end do
        end do
        ok = .true.
    end subroutine line_columns

    !> The tangents' scratch for n active coordinates.
    pure function tangent_work(n) result(tw)
        integer, intent(in) :: n      !! active coordinates
        type(tangent_work_t) :: tw    !! scratch sized for them (zero)
        allocate (tw%cols(n), tw%sgn(n), tw%idx(n), tw%b(n), tw%bd(6, n))
        tw%cols = 0; tw%sgn = 0; tw%idx = 0; tw%b = zero; tw%bd = zero
    end function tangent_work

    !> K += kl b b^T, C += cl b b^T over the nonzero entries of b.
    pure subroutine add_line_tangent(b, kl, cl, kgen, cgen, idx)
        real(wp), intent(in) :: b(:)                     !! (n) the element's row (line_columns)
        real(wp), intent(in) :: kl                       !! dT/dL of its law [N/m]
        real(wp), intent(in) :: cl                       !! dT/dL' of its law [N s/m]
        real(wp), intent(inout) :: kgen(:, :)            !! (n, n) generalized stiffness
        real(wp), intent(inout) :: cgen(:, :)            !! (n, n) generalized damping
        integer, intent(out) :: idx(:)                   !! scratch, at least n long
        integer :: i, nz
        if (kl == zero .and. cl == zero) return
        nz = 0
        do i = 1, size(kgen, 1)
            if (b(i) /= zero) then
                nz = nz + 1
                idx(nz) = i
            end if
        end do
        do i = 1, nz
            kgen(idx(1:nz), idx(i)) = kgen(idx(1:nz), idx(i)) + kl*b(idx(i))*b(idx(1:nz))
            cgen(idx(1:nz), idx(i)) = cgen(idx(1:nz), idx(i)) + cl*b(idx(i))*b(idx(1:nz))
        end do
    end subroutine add_line_tangent

    !> Append one warning line to a list.
    pure subroutine add_warning(warnings, text)
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! the list, one line added
        character(len=*), intent(in) :: text                                   !! the line
        warnings = [character(len=warning_len) :: warnings, text]
    end subroutine add_warning

    !> The channels of a family with the same rows for every element: for
    !! each row k in turn, every element's channel NAME_SUFFIX(k), element
    !! e's at (k - 1) n + e.
    pure function item_channels(names, suffix, units, group, comp) result(c)
        character(len=*), intent(in) :: names(:)    !! (n) the elements' names
        character(len=*), intent(in) :: suffix(:)   !! (rows) each row's suffix, after "_"
        character(len=*), intent(in) :: units(:)    !! (rows) its units
        character(len=*), intent(in) :: group(:)    !! (rows) its listing group
        integer, intent(in) :: comp(:)              !! (rows) its row of the family's output array
        type(family_channel_t), allocatable :: c(:)
        integer :: e, k, n
        n = size(names)
        allocate (c(n*size(suffix)))
        do k = 1, size(suffix)
            do e = 1, n
                c((k - 1)*n + e) = family_channel_t(trim(names(e))//'_'//trim(suffix(k)), trim(units(k)), &
                                                    trim(group(k)), e, comp(k))
            end do
        end do
    end function item_channels

    !> Coordinates on the tree path between bodies ka and kb (0 = R): those
    !! in exactly one of the two chains, ascending, with sign +1 for kb's,
    !! -1 for ka's. The chains are ascending: one merge of the two lists.
    pure subroutine path_columns(tree, ka, kb, cols, sgn, ncol)
        type(body_tree_t), intent(in) :: tree    !! the body tree
        integer, intent(in) :: ka                !! first body (0 = R)
        integer, intent(in) :: kb                !! second body (0 = R)
        integer, intent(out) :: cols(:)          !! the coordinates (ncol set)
        integer, intent(out) :: sgn(:)           !! their signs
        integer, intent(out) :: ncol             !! how many
        integer :: ia, ib, na, nb, ja, jb
        na = 0; nb = 0
        if (ka > 0) na = tree%chain_len(ka)
        if (kb > 0) nb = tree%chain_len(kb)
        ia = 1; ib = 1; ncol = 0
        do while (ia <= na .or. ib <= nb)
            ja = huge(ja); jb = huge(jb)
            if (ia <= na) ja = tree%chain(ia, ka)
            if (ib <= nb) jb = tree%chain(ib, kb)
            if (ja == jb) then          ! on both chains: the two ends move as one
                ia = ia + 1; ib = ib + 1
            else if (jb < ja) then
                ncol = ncol + 1; cols(ncol) = jb; sgn(ncol) = 1
                ib = ib + 1
            else
                ncol = ncol + 1; cols(ncol) = ja; sgn(ncol) = -1
                ia = ia + 1
            end if
        end do
    end subroutine path_columns

    !> The row b_j = d(phi . v_rel)/dxdot_j of body kb's motion relative to
    !! body ka's (0 = R) against a spatial force phi = (moment about the
    !! kinematics' origin; force): b_j = +-sj_j . phi, + on kb's chain, - on
    !! ka's (a contact's or a clamp's rate along a direction).
    pure subroutine spatial_row(tree, kin, ka, kb, phi, cols, sgn, b)
        type(body_tree_t), intent(in) :: tree        !! the body tree
        type(kinematics_t), intent(in) :: kin        !! kinematics: joint columns filled
        integer, intent(in) :: ka                    !! the first body (0 = R)
        integer, intent(in) :: kb                    !! the second body
        real(wp), intent(in) :: phi(6)               !! the spatial force [m, -]
        integer, intent(out) :: cols(:)              !! scratch
        integer, intent(out) :: sgn(:)               !! scratch
        real(wp), intent(out) :: b(:)                !! (n) the row
        integer :: i, ncol
        b = zero
        call path_columns(tree, ka, kb, cols, sgn, ncol)
        do i = 1, ncol
            b(cols(i)) = sgn(i)*dot_product(kin%sj(:, cols(i)), phi)
        end do
    end subroutine spatial_row

end module hn_element_family
