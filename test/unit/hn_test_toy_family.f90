!> A toy element family for the tests, registered only in the models the
!! tests build (model_add_family, or read_case's `families`): linear
!! spring-dampers on single coordinates, Q_j = -k (x_j - x0) - c s(t) xdot_j.
!! It shows what a new family is: one type extending element_family_t with
!! every binding, and nothing else in the code changed for the deck (its
!! card, its repeats refused, CHANGE on its fields), the loads, the
!! structured Jacobian, the channels, the plausibility checks, the scaling,
!! the run's breakpoints (its damping tables) and the run's monitors (its
!! springs' stretch) to use it. Output per spring: its generalized force
!! [N or N m].
!!
!! Its registry line is `toy_registration()` (name CSPRINGS, its card, the
!! family with no springs), the entry a registry family's module exports;
!! a test brings it to a deck as read_case's `families`. It reads its own
!! deck card (`read_card`), which it also names through `deck_cards` for a
!! model built in code (model_add_family):
!!
!!   CSPRING   body      coord     k         c         x0        name      table
!!
!! a spring on coordinate `coord` (TX ... RZ) of `body`, stiffness k
!! [N/m or N m/rad], damping c [N s/m or N m s/rad] (blank: 0), neutral
!! value x0 [m or deg] (blank: 0), and the name of a TABLE whose value
!! s(t) multiplies the damping (blank: s = 1); a card on a locked
!! coordinate is refused, and so is a second card on the same body and
!! coordinate.
module hn_test_toy_family
    use hn_kinds, only: wp, zero, half
    use hn_deck_reader, only: deck_reader_t
    use hn_element_cards, only: card_context_t, family_card_t, active_coordinate, unit_of, unit_factor, unit_limit, &
                                table_ref, unique_coordinate
    use hn_tables, only: table_t, table_value
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t
    use hn_tree, only: body_tree_t
    use hn_family_registration, only: family_registration_t
    use hn_element_family, only: family_slot_t
    use hn_element_family, only: element_family_t, family_work_t, family_channel_t, element_table_t, max_family_items, item_len, &
                                 warning_len, check_range
    use hn_element_family, only: family_energy_t, tangent_work_t
    implicit none
    private

    public :: coord_spring_t, coord_spring_family_t, toy_registration

    !> One spring-damper on one active coordinate.
    type :: coord_spring_t
        character(len=12) :: name = ''
        integer :: dof = 0             !! active coordinate
        real(wp) :: k = zero           !! stiffness [N/m or N m/rad]
        real(wp) :: c = zero           !! damping [N s/m or N m s/rad]
        real(wp) :: x0 = zero          !! neutral value [m or rad]
        integer :: table = 0           !! the family's table s(t) on the damping (0: s = 1)
    end type coord_spring_t

    !> The coordinate springs of a model.
    type, extends(element_family_t) :: coord_spring_family_t
        type(coord_spring_t), allocatable :: items(:)
        type(table_t), allocatable :: tables(:)   !! the damping tables its springs name
    contains
        procedure :: deck_cards => toy_deck_cards
        procedure :: read_card => toy_read_card
        procedure :: count => toy_count
        procedure :: ncomp => toy_ncomp
        procedure :: set_neutral => toy_neutral
        procedure :: add_loads => toy_loads
        procedure :: add_tangent => toy_tangent
        procedure :: switch_count => toy_switch_count
        procedure :: switching => toy_switching
        procedure :: channels => toy_channels
        procedure :: result_table => toy_table
        procedure :: plausibility => toy_plausibility
        procedure :: scale_items => toy_items
        procedure :: scale => toy_scale
        procedure :: stiffen => toy_stiffen
        procedure :: input_tables => toy_input_tables
        procedure :: monitor_count => toy_monitor_count
        procedure :: monitor => toy_monitor
        procedure :: monitor_report => toy_monitor_report
    end type coord_spring_family_t

contains

    !> Number of springs.
    pure integer function toy_count(this) result(n)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        n = size(this%items)
    end function toy_count

    !> One output row: the generalized force.
    pure integer function toy_ncomp(this) result(n)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        n = 1
    end function toy_ncomp

    !> Nothing to set up.
    pure subroutine toy_neutral(this, kin)
        class(coord_spring_family_t), intent(inout) :: this   !! the family (unchanged)
        type(kinematics_t), intent(in) :: kin                 !! neutral kinematics (unused)
    end subroutine toy_neutral

    !> Damping of spring e at time t: c s(t).
    pure real(wp) function toy_damping(this, e, t) result(c)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        integer, intent(in) :: e                           !! the spring
        real(wp), intent(in) :: t                          !! time [s]
        c = this%items(e)%c
        if (this%items(e)%table > 0) c = c*table_value(this%tables(this%items(e)%table), t)
    end function toy_damping

    !> Q_j = -k (x_j - x0) - c s(t) xdot_j; energy k d^2 / 2, dissipation c s(t) xdot^2.
    pure subroutine toy_loads(this, t, kin, x, xd, loads, out, work, energy)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: t                          !! time [s]
        type(kinematics_t), intent(in) :: kin              !! kinematics (unused)
        real(wp), intent(in) :: x(:)                       !! active coordinates
        real(wp), intent(in) :: xd(:)                      !! their rates
        type(body_loads_t), intent(inout) :: loads         !! generalized forces, the springs' added
        real(wp), intent(inout) :: out(:, :)               !! (1, n) generalized forces
        type(family_work_t), intent(inout) :: work         !! scratch (unused)
        type(family_energy_t), intent(inout) :: energy     !! energy stored, power dissipated and absorbed, the family's added
        integer :: e
        do e = 1, size(this%items)
            associate (s => this%items(e))
                out(1, e) = -s%k*(x(s%dof) - s%x0) - toy_damping(this, e, t)*xd(s%dof)
                loads%q(s%dof) = loads%q(s%dof) + out(1, e)
                energy%u_elastic = energy%u_elastic + half*s%k*(x(s%dof) - s%x0)**2
                energy%p_diss = energy%p_diss + toy_damping(this, e, t)*xd(s%dof)**2
            end associate
        end do
    end subroutine toy_loads

    !> K_jj += k, C_jj += c s(t) (the law is linear: its tangent exactly).
    pure subroutine toy_tangent(this, tree, kin, t, x, xd, kgen, cgen, tw)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        type(body_tree_t), intent(in) :: tree              !! the body tree (unused)
        type(kinematics_t), intent(in) :: kin              !! kinematics (unused)
        real(wp), intent(in) :: t                          !! time [s] (unused)
        real(wp), intent(in) :: x(:)                       !! active coordinates (unused)
        real(wp), intent(in) :: xd(:)                      !! their rates (unused)
        real(wp), intent(inout) :: kgen(:, :)              !! generalized stiffness, the springs' added
        real(wp), intent(inout) :: cgen(:, :)              !! generalized damping, the springs' added
        type(tangent_work_t), intent(inout) :: tw          !! scratch sized for the coordinates
        integer :: e
        do e = 1, size(this%items)
            associate (s => this%items(e))
                kgen(s%dof, s%dof) = kgen(s%dof, s%dof) + s%k
                cgen(s%dof, s%dof) = cgen(s%dof, s%dof) + toy_damping(this, e, t)
            end associate
        end do
    end subroutine toy_tangent

    !> No switching functions.
    pure integer function toy_switch_count(this) result(n)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        n = 0
    end function toy_switch_count

    !> No switching functions.
    pure subroutine toy_switching(this, t, kin, x, sw)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: t                          !! time [s]
        type(kinematics_t), intent(in) :: kin              !! kinematics (unused)
        real(wp), intent(in) :: x(:)                       !! active coordinates (unused)
        real(wp), intent(out) :: sw(:)                     !! (0) none
        sw = zero
    end subroutine toy_switching

    !> One channel per spring: CS_name, its generalized force.
    pure function toy_channels(this, tree) result(c)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        type(body_tree_t), intent(in) :: tree              !! the body tree (unused)
        type(family_channel_t), allocatable :: c(:)
        integer :: e
        allocate (c(size(this%items)))
        do e = 1, size(this%items)
            c(e) = family_channel_t('CS_'//this%items(e)%name, 'N m', 'COORD SPRINGS', e, 1)
        end do
    end function toy_channels

    !> No table in the result file.
    pure function toy_table(this) result(tab)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        type(element_table_t) :: tab
        tab%group = ''
    end function toy_table

    !> A stiffness two orders of magnitude or more from 10 N m/rad.
    pure subroutine toy_plausibility(this, tree, warnings)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        type(body_tree_t), intent(in) :: tree              !! the body tree (unused)
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, the springs' added
        integer :: e
        do e = 1, size(this%items)
            call check_range('coordinate spring '//trim(this%items(e)%name)//' k', this%items(e)%k, 10.0_wp, &
                             'N m/rad', warnings)
        end do
    end subroutine toy_plausibility

    !> K, C.
    pure subroutine toy_items(this, items)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        character(len=item_len), intent(out) :: items(max_family_items)   !! the properties
        items = ''
        items(1:2) = [character(len=item_len) :: 'K', 'C']
    end subroutine toy_items

    !> Scale k or c of every spring.
    pure subroutine toy_scale(this, item, factor)
        class(coord_spring_family_t), intent(inout) :: this   !! the family
        character(len=*), intent(in) :: item                  !! K or C
        real(wp), intent(in) :: factor                        !! the factor
        select case (item)
        case ('K'); this%items%k = factor*this%items%k
        case ('C'); this%items%c = factor*this%items%c
        end select
    end subroutine toy_scale

    !> STIFFEN: k.
    pure subroutine toy_stiffen(this, factor)
        class(coord_spring_family_t), intent(inout) :: this   !! the family
        real(wp), intent(in) :: factor                        !! the factor
        this%items%k = factor*this%items%k
    end subroutine toy_stiffen

    !> The toy's registry line: name CSPRINGS; its one card, CSPRING, with no
    !! continuation card, read in deck order, one per body and coordinate
    !! (F1, F2); the family with no springs.
    pure function toy_registration() result(r)
        type(family_registration_t) :: r
        r = family_registration_t('CSPRINGS', [family_card_t('CSPRING', 0, 0, unique=unique_coordinate, &
                                                             coordinate=.true.)], toy_empty)
    end function toy_registration

    !> A toy family with no springs and no tables.
    pure subroutine toy_empty(slot)
        type(family_slot_t), intent(out) :: slot   !! the slot, holding the empty family
        type(coord_spring_t), allocatable :: sp(:)
        type(table_t), allocatable :: tb(:)
        allocate (sp(0), tb(0))
        allocate (slot%f, source=coord_spring_family_t(items=sp, tables=tb))
    end subroutine toy_empty

    !> The cards of its registry line (for a model built in code).
    pure function toy_deck_cards(this) result(c)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        type(family_card_t), allocatable :: c(:)
        type(family_registration_t) :: r
        r = toy_registration()
        c = r%cards
    end function toy_deck_cards

    !> The damping tables: the run lands its steps on their corners.
    pure function toy_input_tables(this) result(tabs)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        type(table_t), allocatable :: tabs(:)
        if (allocated(this%tables)) then
            tabs = this%tables
        else
            allocate (tabs(0))
        end if
    end function toy_input_tables

    !> The monitor watches each spring's stretch.
    pure integer function toy_monitor_count(this) result(n)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        n = size(this%items)
    end function toy_monitor_count

    !> |x_j - x0| of each spring [m or rad].
    pure subroutine toy_monitor(this, x, excess)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: x(:)                       !! active coordinates
        real(wp), intent(out) :: excess(:)                 !! (springs) their stretch
        integer :: e
        do e = 1, size(this%items)
            excess(e) = abs(x(this%items(e)%dof) - this%items(e)%x0)
        end do
    end subroutine toy_monitor

    !> One line per spring, its largest stretch and when; the run's warning
    !! names the spring stretched most.
    pure subroutine toy_monitor_report(this, peak, tpeak, lines, summary)
        class(coord_spring_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: peak(:)                    !! (springs) largest stretch
        real(wp), intent(in) :: tpeak(:)                   !! (springs) when [s]
        character(len=warning_len), allocatable, intent(out) :: lines(:)   !! one line per spring
        character(len=:), allocatable, intent(out) :: summary              !! the spring stretched most
        integer :: e
        allocate (lines(size(peak)))
        do e = 1, size(peak)
            write (lines(e), '(3a,es10.3,a,f8.2,a)') 'coordinate spring ', trim(this%items(e)%name), &
                ': largest stretch ', peak(e), ' at ', 1000*tpeak(e), ' ms'
        end do
        summary = ''
        if (size(peak) > 0) summary = 'WARNING: '//trim(lines(maxloc(peak, dim=1)))
    end subroutine toy_monitor_report

    !> A CSPRING card: one spring more.
    subroutine toy_read_card(this, rd, ctx, i, key)
        class(coord_spring_family_t), intent(inout) :: this   !! the family; out: the spring added
        type(deck_reader_t), intent(inout) :: rd              !! the deck: located field access, the first error
        type(card_context_t), intent(inout) :: ctx            !! the deck's bodies and the reduced tree
        integer, intent(in) :: i                              !! the card's first deck line
        character(len=*), intent(in) :: key                   !! the card name (CSPRING)
        type(coord_spring_t) :: s
        integer :: kb, m, it
        call active_coordinate(rd, i, ctx%tree, ctx%bnames, ctx%bmap, kb, m, s%dof, .false.)
        call rd%real(i, 3, 'stiffness k', 'N/m or N m/rad', s%k, zero, 1.0e9_wp)
        call rd%real(i, 4, 'damping c', 'N s/m or N m s/rad', s%c, zero, 1.0e9_wp, default=zero)
        call rd%real(i, 5, 'neutral value', unit_of(m), s%x0, -unit_limit(m), unit_limit(m), default=zero)
        call rd%name(i, 6, 'spring name', s%name)
        if (rd%failed()) return
        if (len_trim(rd%raw(i, 7)) > 0) then
            it = table_ref(rd, i, 7, ctx%tabs)
            if (rd%failed()) return
            if (.not. allocated(this%tables)) allocate (this%tables(0))
            this%tables = [this%tables, ctx%tabs(it)%tab]
            s%table = size(this%tables)
        end if
        s%x0 = s%x0*unit_factor(m)
        this%items = [this%items, s]
    end subroutine toy_read_card

end module hn_test_toy_family
