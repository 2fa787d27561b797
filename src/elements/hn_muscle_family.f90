!> The MUSCLES family: the paper's viscoelastic muscles (eq 11) and
!! Hill-type muscles (hn_muscle), with their paths through via points
!! (hn_line_elements), behind the element-family interface. The family
!! holds the activation tables (eq 11) and the activation histories (ACTIVATE
!! cards) its muscles refer to. Output per muscle: tension [N], length [m]
!! and activation. The family reads its MUSCLE, HILL, ACTIVATE, VIA,
!! FEEDBACK, SPINDLE, GROUP and FIBRE cards (FIBRE: a Hill muscle's fibre length
!! in the neutral posture); a FEEDBACK card adds postural feedback
!! (hn_feedback) to an activation history, a SPINDLE card a stretch loop to
!! each of its muscles, sampled by the run (control_times, control_update);
!! a GROUP card moves a Hill muscle to another history.
!!
!! Activation dynamics as states of the equations of motion (the family's
!! `state_count`): one activation a_h per activation history h and one per
!! stretch loop, each following the first-order law with separate
!! activation and deactivation time constants (Zajac 1989; the constants
!! 15 and 50 ms of Thelen 2003, S5 of reference/parameters.md),
!!   da/dt = (u - a)/T,  T = tau_act when u >= a, tau_deact otherwise,
!! the history's excitation u_h(t) = min(1, u_ACTIVATE(t) + sum of the
!! excitations u_k held by its FEEDBACK loops), a stretch loop's its own
!! held u_k; a_h(t0) = u0, a stretch loop's 0. A muscle of history h has
!! the activation min(1, a_h + a of its own stretch loop). For a history
!! without loops the state equals activation_value (the ACTIVATE card's
!! closed form), which the family uses where no state vector exists (the
!! statics, the start of a run).
module hn_muscle_family
    use hn_kinds, only: wp, zero, one
    use hn_deck_reader, only: deck_reader_t, int_str
    use hn_element_cards, only: card_context_t, card_t, body_map_t, line_card, body_ref, table_ref, big_length, &
                                big_modulus, continued
    use hn_kinematics, only: kinematics_t
    use hn_loads, only: body_loads_t
    use hn_tree, only: body_tree_t
    use hn_tables, only: table_t, table_value
    use hn_muscle, only: activation_t, activation_value, excitation_value
    use hn_feedback, only: feedback_t, feedback_due, feedback_sample, stretch_sample, feedback_times
    use hn_sorting, only: merge_times
    use hn_line_elements, only: muscle_t, line_geometry_t, muscle_geometries, muscle_tension, muscle_law_value, &
                                apply_muscle_tensions, set_neutral_lengths, muscle_path_points, muscle_hill, max_via, &
                                mirror_muscles, muscle_tensions
    use hn_element_family, only: element_family_t, family_work_t, family_channel_t, element_table_t, max_family_items, item_len, &
                                 warning_len, check_range
    use hn_line_family, only: line_family_t, line_table
    use hn_family_registration, only: family_registration_t
    use hn_element_cards, only: family_card_t, card_first, card_last, unique_element, unique_name, ncont_optional
    use hn_element_family, only: family_slot_t
    use hn_element_family, only: family_energy_t
    implicit none
    private

    public :: muscle_family_t, muscles_of, activation_histories, activation_rate
    public :: muscle_registration

    real(wp), parameter :: ref_muscle_m1 = 3000.0_wp      !! N/m (reference/parameters.md)
    real(wp), parameter :: ref_muscle_m2 = 400.0_wp       !! N s/m

    !> The muscles of a model and the activation inputs they refer to.
    type, extends(line_family_t) :: muscle_family_t
        type(muscle_t), allocatable :: items(:)
        type(table_t), allocatable :: tables(:)              !! activation tables (eq 11) referenced by muscles
        type(activation_t), allocatable :: activations(:)    !! activation histories of Hill-type muscles
        type(feedback_t), allocatable :: feedbacks(:)        !! postural feedback loops on those histories
        integer :: nread = 0   !! muscles read from the deck so far (items holds room for every card until end_cards)
        !> mirror_muscles of the items, set with the neutral lengths (unallocated: none)
        integer, allocatable :: mirror(:)
    contains
        procedure :: read_card => muscle_read_card
        procedure :: end_cards => muscle_end_cards
        procedure :: count => muscle_count
        procedure :: ncomp => muscle_ncomp
        procedure :: set_neutral => muscle_neutral
        procedure :: add_loads => muscle_loads
        procedure :: switch_count => muscle_switch_count
        procedure :: switching => muscle_switching
        procedure :: channels => muscle_channels
        procedure :: result_table => muscle_table
        procedure :: law_plausibility => muscle_plausibility
        procedure :: path => muscle_path
        procedure :: line_tension => muscle_line_tension
        procedure :: line_kind => muscle_kind
        procedure :: scale_items => muscle_items
        procedure :: scale => muscle_scale
        procedure :: stiffen => muscle_stiffen
        procedure :: activation => muscle_activation
        procedure :: control_times => muscle_control_times
        procedure :: control_update => muscle_control_update
        procedure :: input_tables => muscle_input_tables
        procedure :: active_muscle => muscle_active
        procedure :: state_count => muscle_state_count
        procedure :: state_start => muscle_state_start
        procedure :: state_rates => muscle_state_rates
    end type muscle_family_t

contains

    !> Number of muscles.
    pure integer function muscle_count(this) result(n)
        class(muscle_family_t), intent(in) :: this   !! the family
        n = 0
        if (allocated(this%items)) n = size(this%items)
    end function muscle_count

    !> Output rows per muscle: tension, length, activation.
    pure integer function muscle_ncomp(this) result(n)
        class(muscle_family_t), intent(in) :: this   !! the family
        n = 3
    end function muscle_ncomp

    !> Activation a(t) of muscle e: its activation history's state (Hill-type
    !! law) plus the state of its own stretch loop, at most 1 (the
    !! ACTIVATE card's closed form where the family has no states set);
    !! or its table (eq 11); zero without either. Without the stretch loop
    !! `skip`, when given.
    pure real(wp) function muscle_activation(this, e, t, skip) result(act)
        class(muscle_family_t), intent(in) :: this   !! the family
        integer, intent(in) :: e                     !! muscle number
        real(wp), intent(in) :: t                    !! time [s]
        integer, intent(in), optional :: skip        !! a feedback loop left out (its number)
        integer :: k, k_skip
        k_skip = 0
        if (present(skip)) k_skip = skip
        act = history_activation(this, e, t)
        if (.not. loops_apply(this, e)) return
        do k = 1, size(this%feedbacks)
            if (k /= k_skip .and. this%feedbacks(k)%muscle == e) &
                act = min(one, act + this%state(this%feedbacks(k)%state))
        end do
    end function muscle_activation

    !> Activations of every muscle at time t, as muscle_activation gives
    !! them one by one, with one pass over the stretch loops (each muscle's
    !! loops still added in the loops' order): O(muscles + loops).
    pure subroutine muscle_activations(this, t, act)
        class(muscle_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: t                    !! time [s]
        real(wp), intent(out) :: act(:)              !! (count) each muscle's activation
        integer :: e, k
        do e = 1, size(this%items)
            act(e) = history_activation(this, e, t)
        end do
        do k = 1, size(this%feedbacks)
            e = this%feedbacks(k)%muscle
            if (e < 1) cycle
            if (loops_apply(this, e)) act(e) = min(one, act(e) + this%state(this%feedbacks(k)%state))
        end do
    end subroutine muscle_activations

    !> Muscle e's activation without its stretch loops: its history's state
    !! (the closed form where the family has no states set), or its table.
    pure real(wp) function history_activation(this, e, t) result(act)
        class(muscle_family_t), intent(in) :: this   !! the family
        integer, intent(in) :: e                     !! muscle number
        real(wp), intent(in) :: t                    !! time [s]
        act = zero
        associate (m => this%items(e))
            if (m%law == muscle_hill) then
                if (m%history > 0) then
                    if (allocated(this%state)) then
                        act = this%state(m%history)
                    else
                        act = activation_value(this%activations(m%history), t)
                    end if
                end if
            else if (m%activation > 0) then
                act = table_value(this%tables(m%activation), t)
            end if
        end associate
    end function history_activation

    !> Whether muscle e's stretch loops add to its activation: a Hill
    !! muscle with a history, the family's states set.
    pure logical function loops_apply(this, e)
        class(muscle_family_t), intent(in) :: this   !! the family
        integer, intent(in) :: e                     !! muscle number
        loops_apply = allocated(this%state)
        if (loops_apply) loops_apply = this%items(e)%law == muscle_hill .and. this%items(e)%history > 0
    end function loops_apply

    !> Rest lengths not given: the neutral path lengths.
    pure subroutine muscle_neutral(this, kin)
        class(muscle_family_t), intent(inout) :: this   !! the family; out: rest lengths set
        type(kinematics_t), intent(in) :: kin           !! kinematics of the neutral configuration
        call set_neutral_lengths(kin, this%items)
        this%mirror = mirror_muscles(this%items)
    end subroutine muscle_neutral

    !> Tensions along every muscle's path; power absorbed.
    pure subroutine muscle_loads(this, t, kin, x, xd, loads, out, work, energy)
        class(muscle_family_t), intent(in) :: this    !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at (x, xd)
        real(wp), intent(in) :: x(:)                  !! active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)                 !! their rates [m/s, rad/s]
        type(body_loads_t), intent(inout) :: loads    !! loads, the muscles' added
        real(wp), intent(inout) :: out(:, :)          !! (3, nm) tension [N], length [m], activation
        type(family_work_t), intent(inout) :: work    !! scratch (line geometry)
        type(family_energy_t), intent(inout) :: energy !! energy stored, power dissipated and absorbed, the family's added
        associate (gm => work%g)
            call muscle_geometries(kin, this%items, gm, work%seg, this%mirror)
            call muscle_activations(this, t, out(3, :))
            call muscle_tensions(this%items, gm, out(3, :), out(1, :), this%mirror)
            out(2, :) = gm%length
            call apply_muscle_tensions(loads, kin, this%items, work%seg, out(1, :))
            energy%p_muscle = energy%p_muscle + sum(out(1, :)*gm%rate)
        end associate
    end subroutine muscle_loads

    !> One switching function per muscle (its law crossing zero).
    pure integer function muscle_switch_count(this) result(n)
        class(muscle_family_t), intent(in) :: this   !! the family
        n = size(this%items)
    end function muscle_switch_count

    !> The muscles' laws (m1 d + m2 d' + a Fmax or the Hill force): tension starts or stops at zero.
    pure subroutine muscle_switching(this, t, kin, x, sw)
        class(muscle_family_t), intent(in) :: this    !! the family
        real(wp), intent(in) :: t                     !! time [s]
        type(kinematics_t), intent(in) :: kin         !! kinematics at x
        real(wp), intent(in) :: x(:)                  !! active coordinates
        real(wp), intent(out) :: sw(:)                !! (switch_count) the switching functions
        type(line_geometry_t) :: gm(size(this%items)), gseg(max_via + 1, size(this%items))
        real(wp) :: act(size(this%items))
        call muscle_geometries(kin, this%items, gm, gseg, this%mirror)
        call muscle_activations(this, t, act)
        sw = muscle_law_value(this%items, gm%length, gm%rate, act)
    end subroutine muscle_switching

    !> One tension channel per muscle, and an activation channel per Hill-type muscle.
    pure function muscle_channels(this, tree) result(c)
        class(muscle_family_t), intent(in) :: this    !! the family
        type(body_tree_t), intent(in) :: tree         !! the body tree (unused)
        type(family_channel_t), allocatable :: c(:)
        integer :: e, n
        allocate (c(size(this%items) + count(this%items%law == muscle_hill)))
        n = 0
        do e = 1, size(this%items)
            n = n + 1
            c(n) = family_channel_t(this%items(e)%name, 'N', 'MUSCLES', e, 1)
            if (this%items(e)%law == muscle_hill) then
                n = n + 1
                c(n) = family_channel_t('A_'//this%items(e)%name, '-', 'MUSCLE ACTIVATION', e, 3)
            end if
        end do
    end function muscle_channels

    !> /model/elements/muscles with the via points: via_count (ne), via_body
    !! (ne, max_via) and via_point (ne, max_via, 3) as h5py shows them; a
    !! muscle's path runs from point a through its first via_count via
    !! points to point b.
    pure function muscle_table(this) result(tab)
        class(muscle_family_t), intent(in) :: this    !! the family
        type(element_table_t) :: tab
        integer :: e, n
        n = size(this%items)
        tab = line_table(this, 'muscles', 'muscle: tension-only path from point a through its via points to b')
        deallocate (tab%extra)
        allocate (tab%extra(3))
        tab%extra(1)%name = 'via_count'
        tab%extra(1)%units = '1'
        tab%extra(1)%description = 'via points of each muscle path, in order from point a to point b'
        tab%extra(1)%i = [(this%items(e)%nvia, e=1, n)]
        tab%extra(1)%shape = [n]
        tab%extra(2)%name = 'via_body'
        tab%extra(2)%units = '1'
        tab%extra(2)%description = 'bodies of the via points (0 = R, else /model order; unused slots 0)'
        tab%extra(2)%i = [(this%items(e)%via_body, e=1, n)]
        tab%extra(2)%shape = [max_via, n]
        tab%extra(3)%name = 'via_point'
        tab%extra(3)%units = 'm'
        tab%extra(3)%description = 'via points in their body frames from the mass centre (unused slots 0)'
        tab%extra(3)%r = [(this%items(e)%via_point, e=1, n)]
        tab%extra(3)%shape = [3, max_via, n]
    end function muscle_table

    !> Muscle e's m1 and m2 far from the reference model's.
    pure subroutine muscle_plausibility(this, e, warnings)
        class(muscle_family_t), intent(in) :: this    !! the family
        integer, intent(in) :: e                      !! muscle number
        character(len=warning_len), allocatable, intent(inout) :: warnings(:)  !! warnings, the muscle's added
        associate (m => this%items(e))
            call check_range('muscle '//trim(m%name)//' stiffness m1', m%m1, ref_muscle_m1, 'N/m', warnings)
            call check_range('muscle '//trim(m%name)//' damping m2', m%m2, ref_muscle_m2, 'N s/m', warnings)
        end associate
    end subroutine muscle_plausibility

    !> Muscle e's name and its path: origin, via points, insertion.
    pure subroutine muscle_path(this, e, name, bodies, points, npt)
        class(muscle_family_t), intent(in) :: this        !! the family
        integer, intent(in) :: e                          !! muscle number
        character(len=12), intent(out) :: name            !! its name
        integer, intent(out) :: bodies(max_via + 2)       !! the points' bodies
        real(wp), intent(out) :: points(3, max_via + 2)   !! their body-frame positions [m]
        integer, intent(out) :: npt                       !! nvia + 2
        name = this%items(e)%name
        call muscle_path_points(this%items(e), bodies, points, npt)
    end subroutine muscle_path

    !> Muscle e's tension at its activation at time t.
    pure real(wp) function muscle_line_tension(this, e, t, length, rate) result(tension)
        class(muscle_family_t), intent(in) :: this    !! the family
        integer, intent(in) :: e                      !! muscle number
        real(wp), intent(in) :: t                     !! time [s]
        real(wp), intent(in) :: length                !! path length [m]
        real(wp), intent(in) :: rate                  !! its rate [m/s]
        tension = muscle_tension(this%items(e), length, rate, muscle_activation(this, e, t))
    end function muscle_line_tension

    !> 'muscle'.
    pure function muscle_kind(this) result(word)
        class(muscle_family_t), intent(in) :: this    !! the family
        character(len=:), allocatable :: word
        word = 'muscle'
    end function muscle_kind

    !> M1, M2, F0, LENGTH (the Hill muscles' optimal fibre length).
    pure subroutine muscle_items(this, items)
        class(muscle_family_t), intent(in) :: this    !! the family
        character(len=item_len), intent(out) :: items(max_family_items)   !! the properties
        items = ''
        items(1:4) = [character(len=item_len) :: 'M1', 'M2', 'F0', 'LENGTH']
    end subroutine muscle_items

    !> Scale m1, the damping (M2: m2 and the Hill damping) or F0 (with the Hill damping) of every muscle.
    pure subroutine muscle_scale(this, item, factor)
        class(muscle_family_t), intent(inout) :: this   !! the family
        character(len=*), intent(in) :: item            !! M1, M2, F0 or LENGTH
        real(wp), intent(in) :: factor                  !! the factor
        select case (item)
        case ('M1'); this%items%m1 = factor*this%items%m1
        case ('M2')      ! the damping of either law: m2 (eq 11) and the Hill damping
            this%items%m2 = factor*this%items%m2
            this%items%hill%damping = factor*this%items%hill%damping
        case ('F0')      ! Hill-type muscles: F0 and the damping that is proportional to it
            this%items%hill%f0 = factor*this%items%hill%f0
            this%items%hill%damping = factor*this%items%hill%damping
        case ('LENGTH'); this%items%hill%lopt = factor*this%items%hill%lopt
        end select
    end subroutine muscle_scale

    !> STIFFEN: m1.
    pure subroutine muscle_stiffen(this, factor)
        class(muscle_family_t), intent(inout) :: this   !! the family
        real(wp), intent(in) :: factor                  !! the factor
        this%items%m1 = factor*this%items%m1
    end subroutine muscle_stiffen

    !> The muscles of a model's family slot (a copy; none when the slot holds another family).
    pure function muscles_of(fam) result(items)
        class(element_family_t), intent(in) :: fam   !! the slot's family
        type(muscle_t), allocatable :: items(:)
        select type (fam)
        type is (muscle_family_t)
            items = fam%items
        class default
            allocate (items(0))
        end select
    end function muscles_of

    !> The activation tables (eq 11) and the excitation ramps of the
    !! activation histories (u0 to u1 from onset + delay over the rise time,
    !! a step over 1 microsecond): the run lands its steps on their corners,
    !! where the activation states' rates change slope.
    pure function muscle_input_tables(this) result(tabs)
        class(muscle_family_t), intent(in) :: this   !! the family
        type(table_t), allocatable :: tabs(:)
        real(wp), parameter :: shortest_rise = 1.0e-6_wp
        real(wp) :: t1
        integer :: h
        tabs = this%tables
        do h = 1, size(this%activations)
            associate (ah => this%activations(h))
                if (ah%u1 == ah%u0) cycle
                t1 = ah%t_onset + ah%delay
                tabs = [tabs, table_t([t1, t1 + max(ah%rise, shortest_rise)], [ah%u0, ah%u1])]
            end associate
        end do
    end function muscle_input_tables

    !> The muscles are active muscle (a passive state switches them off).
    pure logical function muscle_active(this) result(yes)
        class(muscle_family_t), intent(in) :: this   !! the family
        yes = .true.
    end function muscle_active

    !> The activation histories of a model's family slot (a copy; none when the slot holds another family).
    pure function activation_histories(fam) result(items)
        class(element_family_t), intent(in) :: fam   !! the slot's family
        type(activation_t), allocatable :: items(:)
        select type (fam)
        type is (muscle_family_t)
            items = fam%activations
        class default
            allocate (items(0))
        end select
    end function activation_histories

    !> The sample times in [t0, t1] of every feedback loop, ascending (a
    !! time shared by two loops listed once).
    pure function muscle_control_times(this, t0, t1, tol) result(tk)
        class(muscle_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: t0                   !! start of the run [s]
        real(wp), intent(in) :: t1                   !! its end [s]
        real(wp), intent(in) :: tol                  !! times closer than this are one [s]
        real(wp), allocatable :: tk(:)
        integer :: k
        allocate (tk(0))
        do k = 1, size(this%feedbacks)
            tk = merge_times(tk, feedback_times(this%feedbacks(k), t0, t1, tol), tol)
        end do
    end function muscle_control_times

    !> The run has reached time t (kinematics kin): every loop whose sample
    !! is due takes it (the first call of a run starts every loop); the
    !! stretch loops sense their muscles' path lengths and rates there.
    pure subroutine muscle_control_update(this, t, kin, tol)
        class(muscle_family_t), intent(inout) :: this   !! the family; out: the due loops' samples and holds
        real(wp), intent(in) :: t                       !! time reached [s]
        type(kinematics_t), intent(in) :: kin           !! kinematics of the state there
        real(wp), intent(in) :: tol                     !! time tolerance of a sample time [s]
        type(line_geometry_t), allocatable :: gm(:), seg(:, :)
        integer :: k
        real(wp) :: a_b
        if (any(this%feedbacks%muscle > 0 .and. feedback_due(this%feedbacks, t, tol))) then
            allocate (gm(size(this%items)), seg(max_via + 1, size(this%items)))
            call muscle_geometries(kin, this%items, gm, seg)
        end if
        do k = 1, size(this%feedbacks)
            if (.not. feedback_due(this%feedbacks(k), t, tol)) cycle
            a_b = zero
            if (this%feedbacks(k)%muscle > 0) a_b = muscle_activation(this, this%feedbacks(k)%muscle, t, skip=k)
            associate (fb => this%feedbacks(k))
                if (fb%muscle > 0) then
                    call stretch_sample(fb, t, gm(fb%muscle)%length, gm(fb%muscle)%rate, a_b)
                else
                    call feedback_sample(fb, t, kin%s(:, :, fb%body), kin%omega(:, fb%body))
                end if
            end associate
        end do
    end subroutine muscle_control_update

    !> An ACTIVATE, MUSCLE, HILL, VIA, FEEDBACK, SPINDLE or FIBRE card (the
    !! registry reads ACTIVATE cards before, VIA, FEEDBACK, SPINDLE and FIBRE
    !! cards after the others). A
    !! muscle is kept unless both ends are on one merged body.
    subroutine muscle_read_card(this, rd, ctx, i, key)
        class(muscle_family_t), intent(inout) :: this   !! the family; out: the card's muscle, history or via point added
        type(deck_reader_t), intent(inout) :: rd        !! the deck: card images, located field access, the first error
        type(card_context_t), intent(inout) :: ctx      !! the deck's bodies and tables; out: ninternal counted
        integer, intent(in) :: i                        !! the card's first deck line
        character(len=*), intent(in) :: key             !! the card name
        type(muscle_t) :: mu
        logical :: keep
        integer :: it, n
        select case (key)
        case ('ACTIVATE')
            call activation_card(rd, ctx, i, this%activations)
            return
        case ('VIA')
            call via_card(rd, ctx%cards, i, this%items(1:this%nread), ctx%bnames, ctx%bmap)
            return
        case ('FIBRE')
            call fibre_card(rd, ctx%cards, i, this%items(1:this%nread))
            return
        case ('FEEDBACK')
            call feedback_card(rd, ctx, i, this%activations, this%feedbacks)
            return
        case ('SPINDLE')
            call spindle_card(rd, i, this%activations, this%items(1:this%nread), this%feedbacks)
            return
        case ('GROUP')
            call group_card(rd, i, this%activations, this%items(1:this%nread))
            return
        end select
        ! room for every MUSCLE and HILL card, trimmed by end_cards (appending one by one is quadratic)
        n = ctx%ncards('MUSCLE') + ctx%ncards('HILL')
        if (this%nread == 0 .and. size(this%items) < n) then
            deallocate (this%items)
            allocate (this%items(n))
        end if
        if (key == 'MUSCLE') then
            mu = muscle_t()
            call line_card(rd, ctx, i, 'muscle', mu%line_attach_t, i + 1, 7, keep)
            call rd%real(i, 4, 'stiffness m1', 'N/m', mu%m1, zero, big_modulus)
            call rd%real(i, 5, 'damping m2', 'N s/m', mu%m2, zero, big_modulus)
            call rd%real(i, 6, 'active force Fmax', 'N', mu%fmax, zero, 1.0e6_wp, default=zero)
            if (.not. rd%is_blank(i, 7)) then
                it = table_ref(rd, i, 7, ctx%tabs)
                if (.not. rd%failed()) then
                    this%tables = [this%tables, ctx%tabs(it)%tab]
                    mu%activation = size(this%tables)
                end if
            end if
        else
            mu = muscle_t(law=muscle_hill)
            call line_card(rd, ctx, i, 'muscle', mu%line_attach_t, i + 1, 7, keep)
            call rd%real(i, 4, 'maximum isometric force F0', 'N', mu%hill%f0, zero, 1.0e5_wp)
            call rd%real(i, 5, 'optimal fibre length', 'm', mu%hill%lopt, 1.0e-3_wp, one)
            if (.not. rd%is_blank(i, 6)) mu%history = history_ref(rd, i, 6, this%activations)
            if (mu%history > 0) then
                mu%hill%srs_q = this%activations(mu%history)%srs_q
                mu%hill%srs_range = this%activations(mu%history)%srs_range
            end if
            call rd%real(i, 7, 'damping', 'N s/m', mu%hill%damping, zero, 1.0e5_wp, default=zero)
        end if
        if (.not. keep .or. rd%failed()) return
        this%nread = this%nread + 1
        this%items(this%nread) = mu
    end subroutine muscle_read_card

    !> The muscles read: no room left over; each stretch loop's activation
    !! state numbered after the histories'.
    subroutine muscle_end_cards(this, rd, ctx)
        class(muscle_family_t), intent(inout) :: this   !! the family; out: items trimmed, loops' states numbered
        type(deck_reader_t), intent(inout) :: rd        !! the deck (unused)
        type(card_context_t), intent(inout) :: ctx      !! the deck's cards (unused)
        integer :: k, n
        this%items = this%items(1:this%nread)
        n = size(this%activations)
        do k = 1, size(this%feedbacks)
            if (this%feedbacks(k)%muscle == 0) cycle
            n = n + 1
            this%feedbacks(k)%state = n
        end do
    end subroutine muscle_end_cards

    !> Activation states: one per activation history, one per stretch loop.
    pure integer function muscle_state_count(this) result(n)
        class(muscle_family_t), intent(in) :: this   !! the family
        n = size(this%activations) + count(this%feedbacks%muscle > 0)
    end function muscle_state_count

    !> The activations at the start: each history's bracing level u0, the
    !! stretch loops' zero.
    pure subroutine muscle_state_start(this, s)
        class(muscle_family_t), intent(in) :: this   !! the family
        real(wp), intent(out) :: s(:)                !! (state_count) the start activations
        s = zero
        s(1:size(this%activations)) = this%activations%u0
    end subroutine muscle_state_start

    !> The excitation u_h(t) of activation history h: its ACTIVATE card's
    !! (bracing, then the reflex ramp) plus the excitations its FEEDBACK
    !! loops hold, at most 1.
    pure real(wp) function history_excitation(this, h, t) result(u)
        class(muscle_family_t), intent(in) :: this   !! the family
        integer, intent(in) :: h                     !! the history
        real(wp), intent(in) :: t                    !! time [s]
        integer :: k
        u = excitation_value(this%activations(h), t)
        do k = 1, size(this%feedbacks)
            if (this%feedbacks(k)%history == h .and. this%feedbacks(k)%muscle == 0) u = u + this%feedbacks(k)%uk
        end do
        u = min(one, u)
    end function history_excitation

    !> da/dt = (u - a)/T of every activation state: T = tau_act when u >= a,
    !! else tau_deact.
    pure subroutine muscle_state_rates(this, t, kin, s, sdot)
        class(muscle_family_t), intent(in) :: this   !! the family
        real(wp), intent(in) :: t                    !! time [s]
        type(kinematics_t), intent(in) :: kin        !! kinematics (unused: the loops sample it)
        real(wp), intent(in) :: s(:)                 !! (state_count) the activations
        real(wp), intent(out) :: sdot(:)             !! (state_count) their rates [1/s]
        integer :: h, k
        do h = 1, size(this%activations)
            associate (ah => this%activations(h))
                sdot(h) = activation_rate(history_excitation(this, h, t), s(h), ah%tau_act, ah%tau_deact)
            end associate
        end do
        do k = 1, size(this%feedbacks)
            associate (fb => this%feedbacks(k))
                if (fb%state > 0) sdot(fb%state) = activation_rate(fb%uk, s(fb%state), fb%tau_act, fb%tau_deact)
            end associate
        end do
    end subroutine muscle_state_rates

    !> First-order activation dynamics: (u - a)/T with T = tau_act when the
    !! excitation u is at least the activation a, tau_deact otherwise.
    elemental real(wp) function activation_rate(u, a, tau_act, tau_deact) result(r)
        real(wp), intent(in) :: u           !! excitation
        real(wp), intent(in) :: a           !! activation
        real(wp), intent(in) :: tau_act     !! activation time constant [s]
        real(wp), intent(in) :: tau_deact   !! deactivation time constant [s]
        r = (u - a)/merge(tau_act, tau_deact, u >= a)
    end function activation_rate

    !> An ACTIVATE card: the activation history of Hill-type muscles. A
    !! blank onset is the sled pulse onset: the first time the prescribed
    !! translational acceleration of the root body exceeds 1 g (never, when
    !! it does not).
    subroutine activation_card(rd, ctx, i, activations)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_context_t), intent(in) :: ctx  !! the tree, motions and time span (the pulse onset)
        integer, intent(in) :: i  !! the card's first deck line
        type(activation_t), allocatable, intent(inout) :: activations(:)  !! the histories read; out: this card's added
        type(activation_t) :: ah
        ah = activation_t()
        call rd%name(i, 1, 'history name', ah%name)
        if (rd%failed()) return
        call rd%real(i, 2, 'pre-activation u0', '-', ah%u0, zero, one)
        call rd%real(i, 3, 'reflex activation u1', '-', ah%u1, zero, one)
        if (rd%is_blank(i, 4)) then
            ah%t_onset = ctx%pulse_onset()
        else
            call rd%real(i, 4, 'pulse onset', 's', ah%t_onset, -1.0e4_wp, 1.0e4_wp)
        end if
        call rd%real(i, 5, 'reflex delay', 's', ah%delay, zero, 10.0_wp)
        call rd%real(i, 6, 'rise time', 's', ah%rise, zero, 10.0_wp, default=zero)
        call rd%real(i + 1, 1, 'activation time constant', 's', ah%tau_act, 1.0e-4_wp, 10.0_wp, default=0.015_wp)
        call rd%real(i + 1, 2, 'deactivation time constant', 's', ah%tau_deact, 1.0e-4_wp, 10.0_wp, &
                     default=0.05_wp)
        call rd%real(i + 1, 3, 'short-range stiffness q', '-', ah%srs_q, zero, 1.0e3_wp, default=zero)
        call rd%real(i + 1, 4, 'short-range stiffness range', 'lopt', ah%srs_range, 1.0e-4_wp, one, &
                     default=0.01_wp)
        if (rd%failed()) return
        activations = [activations, ah]
    end subroutine activation_card

    !> A FEEDBACK card: history body axis kp kd delay interval, and on its
    !! optional continuation the integral gain ki, a postural feedback loop
    !! adding to the activation history's muscles (hn_feedback); one per
    !! history and axis. The loop takes the
    !! history's time constants; its sensor is the body as the scene keeps
    !! it (a merged body senses the body that absorbed it).
    subroutine feedback_card(rd, ctx, i, activations, feedbacks)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        type(card_context_t), intent(in) :: ctx  !! the deck's bodies and where the scene put them
        integer, intent(in) :: i  !! the card's deck line
        type(activation_t), intent(in) :: activations(:)  !! the histories read
        type(feedback_t), allocatable, intent(inout) :: feedbacks(:)  !! the loops read; out: this card's added
        type(feedback_t) :: fb
        character(len=10) :: ax
        integer :: kb, k
        fb = feedback_t()
        fb%history = history_ref(rd, i, 1, activations)
        kb = body_ref(rd, i, 2, 'sensor body', ctx%bnames, .false.)
        call rd%choice(i, 3, 'sensor axis (lab)', ['X', 'Y', 'Z'], ax)
        call rd%real(i, 4, 'rotation gain kp', '1/rad', fb%kp, -1.0e3_wp, 1.0e3_wp)
        call rd%real(i, 5, 'angular velocity gain kd', 's/rad', fb%kd, -1.0e2_wp, 1.0e2_wp, default=zero)
        call rd%real(i, 6, 'delay', 's', fb%delay, zero, 1.0_wp, default=zero)
        call rd%real(i, 7, 'sample interval', 's', fb%dt, 1.0e-5_wp, 0.1_wp, default=1.0e-3_wp)
        if (continued(rd, i)) call rd%real(i + 1, 1, 'integral gain ki', '1/(rad s)', fb%ki, -1.0e3_wp, 1.0e3_wp, &
                                           default=zero)
        if (rd%failed()) return
        fb%axis = findloc(['X', 'Y', 'Z'], ax(1:1), dim=1)
        fb%body = ctx%bmap%new(kb)
        if (fb%body == 0) then
            call rd%fail(rd%context(i, 2, 'sensor body')//': the scene merged it into the inertial frame R; '// &
                         'expected a body that moves')
            return
        end if
        fb%tau_act = activations(fb%history)%tau_act
        fb%tau_deact = activations(fb%history)%tau_deact
        do k = 1, size(feedbacks)
            if (feedbacks(k)%history == fb%history .and. feedbacks(k)%axis == fb%axis) then
                call rd%fail(rd%context(i, 3, 'sensor axis (lab)')//': history "'// &
                             trim(activations(fb%history)%name)//'" has a FEEDBACK card on axis '//trim(ax)// &
                             ' already; expected one per history and axis')
                return
            end if
        end do
        feedbacks = [feedbacks, fb]
    end subroutine feedback_card

    !> A SPINDLE card: history kp kd delay interval g ki, a stretch loop
    !! (hn_feedback) on every Hill-type muscle of the activation history,
    !! each sensing its own stretch; one card per history. The loops take
    !! the history's time constants.
    subroutine spindle_card(rd, i, activations, muscles, feedbacks)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's deck line
        type(activation_t), intent(in) :: activations(:)  !! the histories read
        type(muscle_t), intent(in) :: muscles(:)  !! the muscles read
        type(feedback_t), allocatable, intent(inout) :: feedbacks(:)  !! the loops read; out: one per muscle of the history added
        type(feedback_t) :: fb
        integer :: e
        fb = feedback_t()
        fb%history = history_ref(rd, i, 1, activations)
        call rd%real(i, 2, 'stretch gain kp', 'per lopt', fb%kp, zero, 1.0e3_wp)
        call rd%real(i, 3, 'stretch-rate gain kd', 's per lopt', fb%kd, zero, 1.0e2_wp, default=zero)
        call rd%real(i, 4, 'delay', 's', fb%delay, zero, 1.0_wp, default=zero)
        call rd%real(i, 5, 'sample interval', 's', fb%dt, 1.0e-5_wp, 0.1_wp, default=1.0e-3_wp)
        call rd%real(i, 6, 'gain rise per unit activation g', '-', fb%gain_act, zero, 1.0e2_wp, default=zero)
        call rd%real(i, 7, 'stretch integral gain ki', 'per lopt s', fb%ki, zero, 1.0e3_wp, default=zero)
        if (rd%failed()) return
        if (any(feedbacks%muscle > 0 .and. feedbacks%history == fb%history)) then
            call rd%fail(rd%context(i, 1, 'activation history')//': history "'// &
                         trim(activations(fb%history)%name)//'" has a SPINDLE card already; expected one per history')
            return
        end if
        if (.not. any(muscles%history == fb%history .and. muscles%law == muscle_hill)) then
            call rd%fail(rd%context(i, 1, 'activation history')//': no HILL card before it names history "'// &
                         trim(activations(fb%history)%name)//'"; expected the history of Hill-type muscles')
            return
        end if
        fb%tau_act = activations(fb%history)%tau_act
        fb%tau_deact = activations(fb%history)%tau_deact
        do e = 1, size(muscles)
            if (muscles(e)%history /= fb%history .or. muscles(e)%law /= muscle_hill) cycle
            fb%muscle = e
            fb%lopt = muscles(e)%hill%lopt
            feedbacks = [feedbacks, fb]
        end do
    end subroutine spindle_card

    !> A GROUP card: muscle history, the Hill muscle driven by another
    !! activation history (with that history's short-range stiffness), as
    !! if its HILL card named it: a deck that includes a model deck gives
    !! its muscles other groups (left and right, for one).
    subroutine group_card(rd, i, activations, muscles)
        type(deck_reader_t), intent(inout) :: rd  !! the deck: card images, located field access, the first error
        integer, intent(in) :: i  !! the card's deck line
        type(activation_t), intent(in) :: activations(:)  !! the histories read
        type(muscle_t), intent(inout) :: muscles(:)  !! the muscles read; out: the card's moved to the history
        character(len=10) :: nm
        integer :: e, h
        call rd%name(i, 1, 'muscle name', nm)
        if (rd%failed()) return
        h = history_ref(rd, i, 2, activations)
        if (rd%failed()) return
        do e = size(muscles), 1, -1       ! (a loop: no temporary of the name component)
            if (muscles(e)%name == nm .and. muscles(e)%law == muscle_hill) exit
        end do
        if (e == 0) then
            call rd%fail(rd%context(i, 1, 'muscle name')//': found "'//trim(nm)// &
                         '"; expected the name of a HILL card before it')
            return
        end if
        muscles(e)%history = h
        muscles(e)%hill%srs_q = activations(h)%srs_q
        muscles(e)%hill%srs_range = activations(h)%srs_range
    end subroutine group_card

    !> Activation history named in field f (an ACTIVATE card).
    integer function history_ref(rd, i, f, hist) result(ih)
        type(deck_reader_t), intent(inout) :: rd
        integer, intent(in) :: i, f
        type(activation_t), intent(in) :: hist(:)
        character(len=10) :: s
        ih = 0
        call rd%name(i, f, 'activation history', s)
        if (rd%failed()) return
        do ih = size(hist), 1, -1
            if (hist(ih)%name == s) exit
        end do
        if (ih == 0) call rd%fail(rd%context(i, f, 'activation history')//': found "'//trim(s)// &
                                  '"; expected the name of an ACTIVATE card')
    end function history_ref

    !> VIA muscle body x y z: the next via point of a muscle's path (MUSCLE or
    !! HILL card of that name), in order from body a to body b, moved onto
    !! a merged body as the muscle's ends are; a VIA card of a muscle the
    !! scene dropped is dropped with it.
    subroutine via_card(rd, cards, i, muscles, bnames, bmap)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        integer, intent(in) :: i
        type(muscle_t), intent(inout) :: muscles(:)
        character(len=10), intent(in) :: bnames(:)
        type(body_map_t), intent(in) :: bmap
        character(len=10) :: nm, other
        real(wp) :: p(3)
        integer :: e, kb, f, k
        logical :: defined
        call rd%name(i, 1, 'muscle name', nm)
        kb = body_ref(rd, i, 2, 'body', bnames, .true.)
        do f = 1, 3
            call rd%real(i, 2 + f, 'via point', 'm', p(f), -big_length, big_length)
        end do
        if (rd%failed()) return
        do e = size(muscles), 1, -1       ! (a loop: no temporary of the name component)
            if (muscles(e)%name == nm) exit
        end do
        if (e == 0) then
            defined = .false.
            do k = 1, size(cards)
                if (cards(k)%key /= 'MUSCLE' .and. cards(k)%key /= 'HILL') cycle
                call rd%name(cards(k)%first, 1, 'muscle name', other)
                defined = defined .or. other == nm
            end do
            if (.not. defined) call rd%fail(rd%context(i, 1, 'muscle name')//': found "'//trim(nm)// &
                                            '"; expected the name of a MUSCLE or HILL card')
            return
        end if
        associate (m => muscles(e))
            if (m%nvia == max_via) then
                call rd%fail(rd%context(i, 1, 'muscle name')//': muscle "'//trim(nm)//'" has '// &
                             trim(int_str(max_via))//' via points already; expected at most '// &
                             trim(int_str(max_via))//' VIA cards per muscle')
                return
            end if
            if (kb > 0) then
                p = bmap%length*(p + bmap%shift(:, kb))
                kb = bmap%new(kb)
            end if
            m%nvia = m%nvia + 1
            m%via_body(m%nvia) = kb
            m%via_point(:, m%nvia) = p
        end associate
    end subroutine via_card

    !> FIBRE muscle ln: the normalised fibre length lf/lopt of a Hill-type
    !! muscle in the neutral posture (hn_muscle; default 1, the fibres at
    !! their optimal length). A FIBRE card of a muscle the scene dropped is
    !! dropped with it.
    subroutine fibre_card(rd, cards, i, muscles)
        type(deck_reader_t), intent(inout) :: rd
        type(card_t), intent(in) :: cards(:)
        integer, intent(in) :: i
        type(muscle_t), intent(inout) :: muscles(:)
        character(len=10) :: nm, other
        real(wp) :: ln
        integer :: e, k
        logical :: hill
        call rd%name(i, 1, 'muscle name', nm)
        call rd%real(i, 2, 'normalised fibre length at neutral', 'lopt', ln, 0.3_wp, 2.0_wp)
        if (rd%failed()) return
        do e = size(muscles), 1, -1       ! (a loop: no temporary of the name component)
            if (muscles(e)%name == nm) exit
        end do
        if (e > 0) then
            if (muscles(e)%law == muscle_hill) then
                muscles(e)%hill%ln = ln
                return
            end if
        end if
        hill = .false.
        do k = 1, size(cards)
            if (cards(k)%key /= 'HILL') cycle
            call rd%name(cards(k)%first, 1, 'muscle name', other)
            hill = hill .or. other == nm
        end do
        if (.not. hill) call rd%fail(rd%context(i, 1, 'muscle name')//': found "'//trim(nm)// &
                                     '"; expected the name of a HILL card')
    end subroutine fibre_card

    !> The registry's entry of the muscles: name MUSCLES, its cards (MUSCLE
    !! and HILL in deck order; ACTIVATE first, the histories HILL cards name;
    !! VIA, FEEDBACK, SPINDLE, GROUP and FIBRE last, on the muscles and
    !! histories read before), and the family with no elements.
    pure function muscle_registration() result(r)
        type(family_registration_t) :: r
        r = family_registration_t('MUSCLES', [ &
            family_card_t('MUSCLE', 0, 1, unique=unique_element), &
            family_card_t('HILL', 0, 1, unique=unique_element), &
            family_card_t('VIA', 0, 0, card_last), &
            family_card_t('ACTIVATE', 0, 1, card_first, unique_name, what='history name'), &
            family_card_t('FEEDBACK', 0, ncont_optional, card_last), &
            family_card_t('SPINDLE', 0, 0, card_last), &
            family_card_t('GROUP', 0, 0, card_last), &
            family_card_t('FIBRE', 0, 0, card_last, unique_name, what='muscle name')], muscle_empty)
    end function muscle_registration

    !> A family of muscles with no elements (its arrays allocated with size 0, not
    !! taken from a zero-size array constructor, which gfortran copies into
    !! an unallocated component when the model is copied).
    pure subroutine muscle_empty(slot)
        type(family_slot_t), intent(out) :: slot   !! the slot, holding the empty family
        type(muscle_t), allocatable :: m(:)
        type(table_t), allocatable :: tb(:)
        type(activation_t), allocatable :: a(:)
        type(feedback_t), allocatable :: fb(:)
        allocate (m(0), tb(0), a(0), fb(0))
        allocate (slot%f, source=muscle_family_t(items=m, tables=tb, activations=a, feedbacks=fb))
    end subroutine muscle_empty

end module hn_muscle_family
