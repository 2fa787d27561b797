!> The model: body tree, which coordinates are prescribed and how, gravity,
!! element families (one slot per family of the registry hn_families) and
!! applied loads, the posture-holding forces and their release. Everything a
!! dynamics evaluation reads.
module hn_model
    use hn_kinds, only: wp, zero, one, g_std
    use hn_tree, only: body_tree_t
    use hn_motion, only: motion_t
    use hn_applied, only: applied_load_t
    use hn_kinematics, only: kinematics_t, kinematics_allocate, partial_velocities
    use hn_linsolve, only: solver_gauss
    use hn_sorting, only: merge_times
    use hn_element_family, only: element_family_t, family_slot_t, max_family_items, item_len
    use hn_families, only: nfamilies, family_name, new_family
    implicit none
    private

    public :: model_t, model_init, model_set_neutral, neutral_coordinates, family_count, family_items, family_items_text
    public :: scale_family, model_set_family, model_add_family
    public :: hold_factor, hold_pass, hold_unreleased, hold_breakpoints, control_times, control_pass
    ! the registry's names, for the modules that know the model only
    public :: max_family_items, nfamilies, family_name

    !> A complete mechanical model.
    type :: model_t
        character(len=80) :: title = ''
        type(body_tree_t) :: tree
        real(wp) :: gravity(3) = [zero, zero, -g_std]  !! gravitational acceleration in R [m/s^2]
        logical, allocatable :: prescribed(:)          !! (n) coordinate driven by `motion`
        type(motion_t), allocatable :: motion(:)       !! (n) its time history
        !> the element families: the registry's in its order (family_name), then any added by model_add_family
        type(family_slot_t), allocatable :: family(:)
        type(applied_load_t), allocatable :: applied(:)
        real(wp), allocatable :: q_hold(:)             !! (n) generalized forces holding the start posture, full value
        real(wp) :: hold_release = huge(one)           !! HOLD POSTURE release time t_r [s] (huge: never released)
        real(wp) :: hold_duration = zero               !! release duration t_d [s] (0: a step at t_r)
        logical :: hold_stepped = .false.              !! the run has passed the step at t_r: s(t_r) = 0 (hold_pass)
        logical, allocatable :: family_on(:)           !! (size(family)) element families switched on
        integer :: solver = solver_gauss               !! solver of a_ij xddot = f
        character(len=8) :: jacobian = 'STRUCT'        !! Jacobian of the stiff integrators: STRUCT (from the elements) or FD
    end type model_t

contains

    !> Number of elements of family f in the model.
    pure integer function family_count(model, f) result(n)
        type(model_t), intent(in) :: model       !! the model
        integer, intent(in) :: f                 !! family (family_index, or model_add_family's number)
        n = 0
        if (f < 1 .or. f > size(model%family)) return
        n = model%family(f)%f%count()
    end function family_count

    !> Start a model on a built tree: nothing prescribed, no elements.
    pure subroutine model_init(model, tree)
        type(model_t), intent(out) :: model      !! the model, empty
        type(body_tree_t), intent(in) :: tree    !! the built body tree
        integer :: f
        model%tree = tree
        allocate (model%prescribed(tree%ndof), model%motion(tree%ndof), model%q_hold(tree%ndof))
        model%prescribed = .false.
        model%q_hold = zero
        allocate (model%family(nfamilies()), model%family_on(nfamilies()))
        model%family_on = .true.
        do f = 1, nfamilies()
            call new_family(f, model%family(f))
        end do
        allocate (model%applied(0))
    end subroutine model_init

    !> Put family f (elements of the kind the registry names) into the model.
    pure subroutine model_set_family(model, f, fam)
        type(model_t), intent(inout) :: model          !! the model; out: slot f holds a copy of fam
        integer, intent(in) :: f                       !! family (family_index, or model_add_family's number)
        class(element_family_t), intent(in) :: fam     !! the family
        if (allocated(model%family(f)%f)) deallocate (model%family(f)%f)
        allocate (model%family(f)%f, source=fam)
    end subroutine model_set_family

    !> Add a family of a kind the registry does not list (a model built in
    !! code, not from a deck: a test's or an experiment's element type); every
    !! evaluation visits it after the registry's families.
    pure subroutine model_add_family(model, fam, f)
        type(model_t), intent(inout) :: model          !! the model; out: one more family slot, switched on
        class(element_family_t), intent(in) :: fam     !! the family
        integer, intent(out) :: f                      !! its number in the model
        type(family_slot_t), allocatable :: slots(:)
        logical, allocatable :: on(:)
        integer :: i
        f = size(model%family) + 1
        allocate (slots(f), on(f))
        do i = 1, f - 1
            call move_alloc(model%family(i)%f, slots(i)%f)
        end do
        allocate (slots(f)%f, source=fam)
        call move_alloc(slots, model%family)
        on(1:f - 1) = model%family_on
        on(f) = .true.
        call move_alloc(on, model%family_on)
    end subroutine model_add_family

    !> Active coordinates of the neutral configuration (every coordinate at
    !! its reference value).
    pure function neutral_coordinates(model) result(x)
        type(model_t), intent(in) :: model       !! the model
        real(wp) :: x(model%tree%ndof)
        integer :: j
        do j = 1, model%tree%ndof
            x(j) = model%tree%q_ref(model%tree%dof_local(j), model%tree%dof_body(j))
        end do
    end function neutral_coordinates

    !> Measure the neutral configuration: each family's references (disc
    !! plate frames and offsets, the free lengths of line elements not given
    !! explicitly).
    pure subroutine model_set_neutral(model)
        type(model_t), intent(inout) :: model    !! the model; out: disc references and free lengths set
        type(kinematics_t) :: kin
        real(wp) :: x0(model%tree%ndof)
        integer :: f
        x0 = neutral_coordinates(model)
        call kinematics_allocate(model%tree, kin)
        call partial_velocities(model%tree, x0, 0*x0, kin)
        do f = 1, size(model%family)
            call model%family(f)%f%set_neutral(kin)
        end do
    end subroutine model_set_neutral

    !> The factor s(t) on the posture-holding forces q_hold: 1 before the
    !! release time t_r (and always when never released); with a duration
    !! t_d > 0, s = 1 - (3 u^2 - 2 u^3), u = (t - t_r)/t_d, over [t_r, t_r +
    !! t_d] (C1-continuous), 0 after; with t_d = 0 a step: 0 after t_r, and
    !! at t_r itself 1 (the limit from the left, for the step that ends
    !! there) until the run has passed the step (hold_pass), then 0.
    pure real(wp) function hold_factor(model, t) result(s)
        type(model_t), intent(in) :: model       !! the model (its release time and duration)
        real(wp), intent(in) :: t                !! time [s]
        real(wp) :: u
        if (model%hold_stepped) then
            s = zero
        else if (t < model%hold_release) then
            s = one
        else if (model%hold_duration > zero) then
            u = min((t - model%hold_release)/model%hold_duration, one)
            s = one - u*u*(3.0_wp - 2.0_wp*u)
        else if (t > model%hold_release) then
            s = zero
        else
            s = one
        end if
    end function hold_factor

    !> The run has reached time t and restarts there: when t is a step
    !! release's time t_r (within tol), the holding forces are off from now
    !! on, t_r included (the limit from the right).
    pure subroutine hold_pass(model, t, tol)
        type(model_t), intent(inout) :: model    !! the model; out: hold_stepped set at a step release
        real(wp), intent(in) :: t                !! the time reached [s]
        real(wp), intent(in) :: tol              !! time tolerance of a breakpoint [s]
        if (model%hold_duration == zero .and. abs(t - model%hold_release) <= tol) model%hold_stepped = .true.
    end subroutine hold_pass

    !> The times in [t0, t1] at which the controllers of any family sample
    !! the state (FEEDBACK cards), ascending; the run ends a step at each
    !! one, without a restart (the inputs stay continuous there).
    pure function control_times(model, t0, t1, tol) result(tk)
        type(model_t), intent(in) :: model       !! the model
        real(wp), intent(in) :: t0               !! start of the run [s]
        real(wp), intent(in) :: t1               !! its end [s]
        real(wp), intent(in) :: tol              !! times closer than this are one [s]
        real(wp), allocatable :: tk(:)
        integer :: f
        allocate (tk(0))
        do f = 1, size(model%family)
            if (model%family_on(f)) tk = merge_times(tk, model%family(f)%f%control_times(t0, t1, tol), tol)
        end do
    end function control_times

    !> The run has reached time t, the kinematics of its state kin: the
    !! controllers of every family whose sample is due take it.
    pure subroutine control_pass(model, t, kin, tol)
        type(model_t), intent(inout) :: model    !! the model; out: the controllers' samples and holds
        real(wp), intent(in) :: t                !! time reached [s]
        type(kinematics_t), intent(in) :: kin    !! kinematics of the state at t
        real(wp), intent(in) :: tol              !! time tolerance of a sample time [s]
        integer :: f
        do f = 1, size(model%family)
            if (model%family_on(f)) call model%family(f)%f%control_update(t, kin, tol)
        end do
    end subroutine control_pass

    !> Hold the posture for good: no release (an analysis of the held state).
    pure subroutine hold_unreleased(model)
        type(model_t), intent(inout) :: model    !! the model; out: never released
        model%hold_release = huge(one)
        model%hold_duration = zero
        model%hold_stepped = .false.
    end subroutine hold_unreleased

    !> The breakpoints tb with the release times t_r (and t_r + t_d of a
    !! smooth release) that lie in (t_start, t_end) inserted, in order; a
    !! time within same_time of one already there is not repeated.
    pure function hold_breakpoints(model, tb, t_start, t_end, same_time) result(tbr)
        type(model_t), intent(in) :: model       !! the model (its release)
        real(wp), intent(in) :: tb(:)            !! breakpoints, ascending [s]
        real(wp), intent(in) :: t_start          !! start of the run [s]
        real(wp), intent(in) :: t_end            !! end of the run [s]
        real(wp), intent(in) :: same_time        !! times closer than this are one breakpoint [s]
        real(wp), allocatable :: tbr(:)
        real(wp) :: tr(2)
        integer :: k, i
        tbr = tb
        if (model%hold_release >= huge(one)) return
        tr = [model%hold_release, model%hold_release + model%hold_duration]
        do k = 1, merge(2, 1, model%hold_duration > zero)
            if (tr(k) <= t_start .or. tr(k) >= t_end) cycle
            if (any(abs(tbr - tr(k)) <= same_time)) cycle
            i = count(tbr < tr(k))
            tbr = [tbr(1:i), tr(k), tbr(i + 1:)]
        end do
    end function hold_breakpoints

    !> Properties of a family that a FAMILY parameter may scale.
    pure function family_items(f) result(items)
        integer, intent(in) :: f                 !! family (family_index, or model_add_family's number)
        character(len=item_len) :: items(max_family_items)
        type(family_slot_t) :: slot
        items = ''
        if (f < 1 .or. f > nfamilies()) return
        call new_family(f, slot)
        call slot%f%scale_items(items)
    end function family_items

    !> The properties of a family that a FAMILY parameter may scale, as text: "A, B or C".
    pure function family_items_text(f) result(s)
        integer, intent(in) :: f                 !! family (family_index, or model_add_family's number)
        character(len=:), allocatable :: s
        character(len=item_len) :: items(max_family_items)
        integer :: k, n
        items = family_items(f)
        n = count(len_trim(items) > 0)
        s = trim(items(1))
        do k = 2, n
            if (k == n) then
                s = s//' or '//trim(items(k))
            else
                s = s//', '//trim(items(k))
            end if
        end do
    end function family_items_text

    !> Multiply one property of every element of a family by `factor`.
    pure subroutine scale_family(model, f, item, factor)
        type(model_t), intent(inout) :: model    !! the model
        integer, intent(in) :: f                 !! family (family_index, or model_add_family's number)
        character(len=*), intent(in) :: item     !! property, one of family_items(f)
        real(wp), intent(in) :: factor           !! the factor
        call model%family(f)%f%scale(item, factor)
    end subroutine scale_family

end module hn_model
