!> One dynamics evaluation: prescribed motions, kinematics, loads, a_ij and
!! f_i, the partition into free and prescribed coordinates, and the solve
!! a_FF xddot_F = f_F - a_FP xddot_P. Also the model as an ODE system
!! y = (x_F, xdot_F, s, E) for the integrators: s the element families'
!! states (each family's `state_count` of them, in the registry's order:
!! the muscles' activations), and the four quadratures E the energy-audit
!! integrals: energy dissipated (discs, springs, joint dampers), energy
!! absorbed by the muscles, work of the applied tables and work done by the
!! prescribed motions. E stays last, so the quadratures trail the state as
!! the integrators expect (hn_ode); a model without states has y = (x_F,
!! xdot_F, E) as before. Every evaluation at a state gives the families
!! their states first (set_element_states).
!!
!! Posture holding released (HOLD POSTURE with a release time): the holding
!! forces s(t) q_hold have the potential e_hold = -s(t) q_hold . x, whose
!! explicit change in time is the work of the release, W_r = integral of
!! -sdot q_hold . x dt. It is counted with the applied-load work (the third
!! quadrature, W_APPLIED): the release is an applied load changing in time
!! like the force and couple tables, and the state, its four quadratures, the
!! channels and every listing without a release stay as they were. A step
!! release makes sdot a delta, so W_r is integrated by parts:
!! W_r = (1 - s) q_hold . x + integral of (s - 1) q_hold . xdot dt, the
!! integrand finite on both sides of the step and zero before the release
!! (hn_forces adds it to p_applied; energy_terms adds the first term).
module hn_dynamics
    use hn_kinds, only: wp, zero, one, msglen, deg
    use hn_status, only: stat_ok, stat_gimbal
    use hn_model, only: model_t
    use hn_kinematics, only: kinematics_t, kinematics_allocate, partial_velocities, body_kinematics, kinetic_energy
    use hn_loads, only: body_loads_t, loads_allocate
    use hn_kane, only: a_ij, f_i
    use hn_recursive, only: composite_rigid_body, f_recursive, inertia_times, articulated_body_solve, aba_work_t, &
                            aba_work_allocate
    use hn_jacobian, only: generalized_tangent
    use hn_forces, only: compute_loads, element_output_t, element_output_allocate
    use hn_linsolve, only: linear_solve, solver_gauss, solver_articulated
    use hn_motion, only: motion_eval
    use hn_tree, only: dof_label
    use hn_ode, only: ode_system_t
    implicit none
    private

    public :: dyn_workspace_t, dynamics_setup, dynamics_evaluate, dynamics_outputs, inertia_forces_free
    public :: model_ode_t, model_ode_init
    public :: state_to_coordinates, coordinates_to_state, nenergy, state_size, energy_terms, energy_t
    public :: set_element_states, energy_integrals

    integer, parameter :: nenergy = 4   !! energy-audit quadratures appended to the state
    real(wp), parameter :: cos_singular = 0.01_wp   !! |cos(beta)| below which the Bryant axes are called singular

    !> Work arrays of a dynamics evaluation and the results of the last one.
    type :: dyn_workspace_t
        integer :: ndof = 0, nfree = 0, npres = 0
        integer, allocatable :: ifree(:), ipres(:)  !! free and prescribed coordinate numbers
        integer :: free_offset = -1                 !! ifree = free_offset + (1..nfree) when contiguous, else -1
        type(kinematics_t) :: kin
        type(body_loads_t) :: loads
        type(element_output_t) :: eo                 !! element forces of the last evaluation
        type(aba_work_t) :: aba                      !! work arrays of the articulated-body solve
        real(wp), allocatable :: x(:), xd(:), xdd(:) !! all active coordinates, rates, accelerations
        real(wp), allocatable :: a(:, :), f(:)       !! a_ij and f_i of all active coordinates
        real(wp), allocatable :: aff(:, :), bf(:)    !! the free partition and its right-hand side
        real(wp), allocatable :: lambda(:)           !! constraint forces of the prescribed coordinates
        real(wp) :: p_prescribed = zero              !! power of the prescribed motions [W]
        integer, allocatable :: gimbal_bodies(:)     !! bodies whose first and third Bryant angles are both free
        integer :: nstate = 0                        !! element families' states in the ODE state
        integer, allocatable :: state_first(:)       !! (nfamily) each family's first state - 1 within s
        real(wp), allocatable :: s0(:)               !! (nstate) the states' start values
    end type dyn_workspace_t

    !> The terms of the energy balance at one instant [J]:
    !! kinetic + gravity + elastic + holding + dissipated + muscle
    !! - applied - prescribed = constant.
    type :: energy_t
        real(wp) :: kinetic = zero, gravity = zero, elastic = zero, hold = zero
        real(wp) :: kinetic_rel = zero   !! kinetic energy relative to the root's translation (a scale, not a term)
        real(wp) :: dissipated = zero, muscle = zero, applied = zero, prescribed = zero
        real(wp) :: total = zero
    end type energy_t

    !> The model as a first-order system for the integrators.
    type, extends(ode_system_t) :: model_ode_t
        type(model_t) :: model
        type(dyn_workspace_t) :: ws
    contains
        procedure :: rhs => model_rhs
        procedure :: second_order_tangent => model_tangent
    end type model_ode_t

contains

    !> Size the workspace for a model.
    pure subroutine dynamics_setup(model, ws)
        type(model_t), intent(in) :: model         !! the model (tree, prescribed coordinates, elements)
        type(dyn_workspace_t), intent(out) :: ws   !! sized for it, free/prescribed partition filled
        integer :: n, j, i1, i2
        n = model%tree%ndof
        ws%ndof = n
        ws%npres = count(model%prescribed)
        ws%nfree = n - ws%npres
        allocate (ws%ifree(ws%nfree), ws%ipres(ws%npres))
        i1 = 0; i2 = 0
        do j = 1, n
            if (model%prescribed(j)) then
                i2 = i2 + 1; ws%ipres(i2) = j
            else
                i1 = i1 + 1; ws%ifree(i1) = j
            end if
        end do
        if (ws%nfree > 0) then
            if (ws%ifree(ws%nfree) - ws%ifree(1) + 1 == ws%nfree) ws%free_offset = ws%ifree(1) - 1
        end if
        call kinematics_allocate(model%tree, ws%kin)
        call loads_allocate(ws%loads, model%tree%nbody, n)
        call element_output_allocate(model, ws%eo)
        call aba_work_allocate(model%tree, ws%aba)
        allocate (ws%x(n), ws%xd(n), ws%xdd(n), ws%a(n, n), ws%f(n))
        allocate (ws%aff(ws%nfree, ws%nfree), ws%bf(ws%nfree), ws%lambda(n))
        ws%x = zero; ws%xd = zero; ws%xdd = zero; ws%a = zero; ws%f = zero; ws%lambda = zero
        allocate (ws%state_first(size(model%family)))
        ws%nstate = 0
        do j = 1, size(model%family)
            ws%state_first(j) = ws%nstate
            ws%nstate = ws%nstate + model%family(j)%f%state_count()
        end do
        allocate (ws%s0(ws%nstate))
        do j = 1, size(model%family)
            associate (fam => model%family(j)%f, i0 => ws%state_first(j))
                call fam%state_start(ws%s0(i0 + 1:i0 + fam%state_count()))
            end associate
        end do
        ws%gimbal_bodies = pack([(j, j=1, model%tree%nbody)], [(free_rotation(j, 4) .and. free_rotation(j, 6), &
                                                                 j=1, model%tree%nbody)])
    contains
        pure logical function free_rotation(k, m)
            integer, intent(in) :: k, m
            integer :: jj
            jj = model%tree%dof_index(m, k)
            free_rotation = .false.
            if (jj > 0) free_rotation = .not. model%prescribed(jj)
        end function free_rotation
    end subroutine dynamics_setup

    !> Fill all active coordinates from the free ones and the prescribed motions at t.
    pure subroutine state_to_coordinates(model, ws, t, xf, xdf)
        type(model_t), intent(in) :: model           !! the model (prescribed motions)
        type(dyn_workspace_t), intent(inout) :: ws   !! out: ws%x, ws%xd, and ws%xdd of the prescribed coordinates
        real(wp), intent(in) :: t                    !! time [s]
        real(wp), intent(in) :: xf(:)                !! free coordinates x_F [m, rad]
        real(wp), intent(in) :: xdf(:)               !! their rates xdot_F [m/s, rad/s]
        integer :: i, j
        do i = 1, ws%nfree      ! element by element: a vector subscript would make a heap temporary
            ws%x(ws%ifree(i)) = xf(i)
            ws%xd(ws%ifree(i)) = xdf(i)
        end do
        do i = 1, ws%npres
            j = ws%ipres(i)
            call motion_eval(model%motion(j), t, ws%x(j), ws%xd(j), ws%xdd(j))
        end do
    end subroutine state_to_coordinates

    !> Pack the free coordinates and rates of full arrays into a state
    !! vector, the element states at their start values, energy-audit
    !! integrals zero.
    pure subroutine coordinates_to_state(ws, x, xd, y)
        type(dyn_workspace_t), intent(in) :: ws   !! the free coordinate numbers, the states' start values
        real(wp), intent(in) :: x(:)              !! all active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)             !! their rates [m/s, rad/s]
        real(wp), intent(out) :: y(:)             !! state (x_F, xdot_F, s0, E) with E = 0
        y = zero
        y(1:ws%nfree) = x(ws%ifree)
        y(ws%nfree + 1:2*ws%nfree) = xd(ws%ifree)
        y(2*ws%nfree + 1:2*ws%nfree + ws%nstate) = ws%s0
    end subroutine coordinates_to_state

    !> Give every element family its states from the state vector y.
    pure subroutine set_element_states(model, ws, y)
        type(model_t), intent(inout) :: model     !! the model; out: each family's states set
        type(dyn_workspace_t), intent(in) :: ws   !! the states' places
        real(wp), intent(in) :: y(:)              !! state (x_F, xdot_F, s, E)
        integer :: f, i0, n
        if (ws%nstate == 0) return
        do f = 1, size(model%family)
            n = model%family(f)%f%state_count()
            if (n == 0) cycle
            i0 = 2*ws%nfree + ws%state_first(f)
            call model%family(f)%f%set_state(y(i0 + 1:i0 + n))
        end do
    end subroutine set_element_states

    !> The energy-audit integrals E of a state vector (its last nenergy components).
    pure function energy_integrals(y) result(e)
        real(wp), intent(in) :: y(:)   !! state (x_F, xdot_F, s, E)
        real(wp) :: e(nenergy)
        e = y(size(y) - nenergy + 1:)
    end function energy_integrals

    !> Accelerations of the free coordinates at (t, xf, xdf); the
    !! kinematics, loads, element outputs and xddot stay in ws for output.
    !! By model%solver: GAUSS, the paper's path (partial velocities, a_ij by
    !! eq 17, f_i by eq 18, Gaussian elimination); CHOLESKY, the same
    !! equations by the composite-rigid-body and recursive Newton-Euler
    !! forms and a Cholesky solve (a_ij and f_i in ws as well); ABA,
    !! the O(n) articulated-body algorithm (ws%a, ws%f not formed).
    pure subroutine dynamics_evaluate(model, ws, t, xf, xdf, xddf, stat, errmsg)
        type(model_t), intent(in) :: model             !! the model
        type(dyn_workspace_t), intent(inout) :: ws     !! workspace from dynamics_setup; out: this evaluation
        real(wp), intent(in) :: t                      !! time [s]
        real(wp), intent(in) :: xf(:)                  !! free coordinates x_F [m, rad]
        real(wp), intent(in) :: xdf(:)                 !! their rates xdot_F [m/s, rad/s]
        real(wp), intent(out) :: xddf(:)               !! free accelerations xddot_F [m/s^2, rad/s^2] (0 on failure)
        integer, intent(out) :: stat                   !! stat_ok; stat_gimbal, stat_singular or stat_ill_conditioned
        character(len=msglen), intent(out) :: errmsg   !! time, failure and coordinate or body ('' when stat_ok)
        integer :: i, j, k

        call state_to_coordinates(model, ws, t, xf, xdf)
        call gimbal_check(model, ws, t, stat, errmsg)
        if (stat /= stat_ok) then
            xddf = zero
            return
        end if
        select case (model%solver)
        case (solver_gauss)
            call partial_velocities(model%tree, ws%x, ws%xd, ws%kin)
            call compute_loads(model, t, ws%kin, ws%x, ws%xd, ws%loads, ws%eo)
            call a_ij(model%tree, ws%kin, ws%a)
            call f_i(model%tree, ws%kin, ws%loads, ws%f)
        case (solver_articulated)
            call body_kinematics(model%tree, ws%x, ws%xd, ws%kin)
            call compute_loads(model, t, ws%kin, ws%x, ws%xd, ws%loads, ws%eo)
            call articulated_body_solve(model%tree, ws%kin, ws%loads, model%prescribed, ws%xdd, ws%lambda, stat, k, &
                                        ws%aba)
            if (stat /= stat_ok) then
                write (errmsg, '(a,es12.5,3a)') 't = ', t, ' s: the joint of body ', trim(model%tree%name(max(k, 1))), &
                    ' has dependent axes (articulated inertia singular)'
                xddf = zero
                return
            end if
            ws%p_prescribed = zero
            do i = 1, ws%nfree
                xddf(i) = ws%xdd(ws%ifree(i))
            end do
            do i = 1, ws%npres
                ws%p_prescribed = ws%p_prescribed + ws%lambda(ws%ipres(i))*ws%xd(ws%ipres(i))
            end do
            errmsg = ''
            return
        case default
            call body_kinematics(model%tree, ws%x, ws%xd, ws%kin)
            call compute_loads(model, t, ws%kin, ws%x, ws%xd, ws%loads, ws%eo)
            call composite_rigid_body(model%tree, ws%kin, ws%a)
            call f_recursive(model%tree, ws%kin, ws%loads, ws%f)
        end select

        call free_block(ws, ws%a, ws%aff)
        ws%bf = ws%f(ws%ifree)
        do i = 1, ws%npres
            ws%bf = ws%bf - ws%a(ws%ifree, ws%ipres(i))*ws%xdd(ws%ipres(i))
        end do
        stat = stat_ok
        errmsg = ''
        if (ws%nfree > 0) call linear_solve(model%solver, ws%aff, ws%bf, stat, errmsg, k)
        if (stat /= 0) then
            write (errmsg, '(a,es12.5,4a)') 't = ', t, ' s: ', trim(errmsg), ' at coordinate ', &
                trim(dof_label(model%tree, ws%ifree(max(1, min(k, ws%nfree)))))
            xddf = zero
            return
        end if
        xddf = ws%bf
        ws%xdd(ws%ifree) = xddf
        ! power of the prescribed motions: lambda_P . xdot_P, with the
        ! generalized constraint forces lambda_P = a_P. xddot - f_P
        ws%p_prescribed = zero
        do i = 1, ws%npres
            j = ws%ipres(i)
            ws%lambda(j) = dot_product(ws%a(j, :), ws%xdd) - ws%f(j)
            ws%p_prescribed = ws%p_prescribed + ws%lambda(j)*ws%xd(j)
        end do
    end subroutine dynamics_evaluate

    !> The free-free block of an (n, n) matrix (a slice when the free
    !! coordinates are contiguous, as when a root body is prescribed).
    pure subroutine free_block(ws, a, aff)
        type(dyn_workspace_t), intent(in) :: ws
        real(wp), intent(in) :: a(:, :)
        real(wp), intent(out) :: aff(:, :)
        integer :: f0, nf
        f0 = ws%free_offset
        nf = ws%nfree
        if (f0 >= 0) then
            aff = a(f0 + 1:f0 + nf, f0 + 1:f0 + nf)
        else
            aff = a(ws%ifree, ws%ifree)
        end if
    end subroutine free_block

    !> The Bryant sequence is singular at cos(beta) = 0 when the first and
    !! third angles are both unknowns: stop there rather than integrate a
    !! nearly singular a_ij.
    pure subroutine gimbal_check(model, ws, t, stat, errmsg)
        type(model_t), intent(in) :: model
        type(dyn_workspace_t), intent(in) :: ws
        real(wp), intent(in) :: t
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        integer :: i, j, k
        real(wp) :: beta
        stat = stat_ok
        errmsg = ''
        do i = 1, size(ws%gimbal_bodies)
            k = ws%gimbal_bodies(i)
            j = model%tree%dof_index(5, k)
            if (j > 0) then
                beta = ws%x(j)
            else
                beta = model%tree%q_ref(5, k)
            end if
            if (abs(cos(beta)) < cos_singular) then
                stat = stat_gimbal
                write (errmsg, '(a,es12.5,3a,f8.3,a)') 't = ', t, ' s: Bryant-angle singularity: body ', &
                    trim(model%tree%name(k)), ' has RY = ', beta/deg, &
                    ' deg (90 deg is singular: its RX and RZ axes coincide); lock or prescribe RX or RZ, or '// &
                    'choose body axes that keep RY away from 90 deg'
                return
            end if
        end do
    end subroutine gimbal_check

    !> The lean evaluation for outputs at (t, xf, xdf): fill the workspace
    !! as dynamics_evaluate would -- coordinates, kinematics, element loads
    !! and outputs, xddot -- without forming a_ij. The free accelerations
    !! are either given (xddf, for instance the derivative of the
    !! integrator's dense output) or solved by the articulated-body
    !! algorithm on the kinematics and loads just computed (exact, O(n)).
    !! Body accelerations then follow from body_accelerations(tree,
    !! ws%kin, ws%xdd, ...). ws%a, ws%f and p_prescribed are left as they are.
    pure subroutine dynamics_outputs(model, ws, t, xf, xdf, stat, xddf)
        type(model_t), intent(in) :: model             !! the model
        type(dyn_workspace_t), intent(inout) :: ws     !! from dynamics_setup; out: coordinates, kinematics, loads, xdd
        real(wp), intent(in) :: t                      !! time [s]
        real(wp), intent(in) :: xf(:)                  !! free coordinates x_F [m, rad]
        real(wp), intent(in) :: xdf(:)                 !! their rates xdot_F [m/s, rad/s]
        integer, intent(out) :: stat                   !! stat_ok, or stat_singular from the solve
        real(wp), intent(in), optional :: xddf(:)      !! free accelerations at t (else solved)
        integer :: k, i
        call state_to_coordinates(model, ws, t, xf, xdf)
        call body_kinematics(model%tree, ws%x, ws%xd, ws%kin)
        call compute_loads(model, t, ws%kin, ws%x, ws%xd, ws%loads, ws%eo)
        stat = stat_ok
        if (present(xddf)) then
            do i = 1, ws%nfree
                ws%xdd(ws%ifree(i)) = xddf(i)
            end do
        else
            call articulated_body_solve(model%tree, ws%kin, ws%loads, model%prescribed, ws%xdd, ws%lambda, stat, k, &
                                        ws%aba)
        end if
    end subroutine dynamics_outputs

    !> Generalized inertia forces a_FF xddot_F of the free coordinates for
    !! given free accelerations (prescribed ones zero), with the kinematics
    !! of the last evaluation in ws; O(n), on every solver path.
    pure function inertia_forces_free(model, ws, xddf) result(q)
        type(model_t), intent(in) :: model        !! the model (its tree)
        type(dyn_workspace_t), intent(in) :: ws   !! kinematics of the last evaluation (joint columns, inertias)
        real(wp), intent(in) :: xddf(:)           !! free accelerations xddot_F [m/s^2, rad/s^2]
        real(wp) :: q(size(xddf)), v(ws%ndof), av(ws%ndof)
        v = zero
        v(ws%ifree) = xddf
        av = inertia_times(model%tree, ws%kin, v)
        q = av(ws%ifree)
    end function inertia_forces_free

    !> Energy terms from the workspace of the evaluation at a state and the
    !! state's four energy-audit integrals equad; the holding potential and
    !! the release work with the evaluation's release factor s (module doc).
    pure function energy_terms(model, ws, equad) result(e)
        type(model_t), intent(in) :: model        !! the model (masses, gravity, holding forces)
        type(dyn_workspace_t), intent(in) :: ws   !! the evaluation at the state (kinematics, element energy)
        real(wp), intent(in) :: equad(nenergy)    !! the state's energy-audit integrals E [J]
        type(energy_t) :: e
        integer :: k, root
        real(wp) :: dv(3), ir(3, 3), om(3), qx
        e%kinetic = kinetic_energy(model%tree, ws%kin)
        root = findloc(model%tree%parent, 0, dim=1)
        do k = 1, model%tree%nbody
            e%gravity = e%gravity - model%tree%mass(k)*dot_product(model%gravity, ws%kin%r(:, k))
            if (k == root) cycle
            dv = ws%kin%v(:, k) - ws%kin%v(:, root)
            ir = ws%kin%inertia_r(:, :, k)     ! fixed-size copies keep the product inline
            om = ws%kin%omega(:, k)
            e%kinetic_rel = e%kinetic_rel + 0.5_wp*model%tree%mass(k)*dot_product(dv, dv) + &
                            0.5_wp*dot_product(om, matmul(ir, om))
        end do
        e%elastic = ws%eo%energy%u_elastic
        qx = dot_product(model%q_hold, ws%x)
        e%hold = -qx
        e%dissipated = equad(1)
        e%muscle = equad(2)
        e%applied = equad(3)
        if (ws%eo%hold_factor /= one) then      ! released in part or in full
            e%hold = zero - ws%eo%hold_factor*qx  ! zero - : +0, not -0, once released
            e%applied = e%applied + (one - ws%eo%hold_factor)*qx
        end if
        e%prescribed = equad(4)
        e%total = e%kinetic + e%gravity + e%elastic + e%hold + e%dissipated + e%muscle - e%applied - e%prescribed
    end function energy_terms

    !> Length of the state vector y = (x_F, xdot_F, s, E) of a model system.
    pure integer function state_size(sys) result(n)
        type(model_ode_t), intent(in) :: sys   !! a system from model_ode_init
        n = 2*sys%ws%nfree + sys%ws%nstate + nenergy
    end function state_size

    !> Wrap a model as an ODE system: y = (x_F, xdot_F, s, E), second-order
    !! structure of size nfree; the structured tangent (model_tangent) is
    !! offered unless model%jacobian is 'FD'. The families hold their
    !! states' start values.
    subroutine model_ode_init(sys, model)
        type(model_ode_t), intent(out) :: sys   !! the system (a copy of the model, its workspace)
        type(model_t), intent(in) :: model      !! the model to wrap
        real(wp), allocatable :: y(:)
        sys%model = model
        sys%nquad = nenergy
        call dynamics_setup(sys%model, sys%ws)
        sys%nsecond = sys%ws%nfree
        sys%has_tangent = model%jacobian /= 'FD'
        allocate (y(state_size(sys)))
        y = zero
        y(2*sys%ws%nfree + 1:2*sys%ws%nfree + sys%ws%nstate) = sys%ws%s0
        call set_element_states(sys%model, sys%ws, y)
    end subroutine model_ode_init

    !> Mass a_FF, stiffness K_FF and damping C_FF of the free coordinates at
    !! (t, y): a_ij by the composite-rigid-body recursion, K and C of the
    !! elements (hn_jacobian), the elements' states those of y. The
    !! structured Jacobian of the stiff methods (the states' own block is
    !! the iteration matrix's, hn_iteration_matrix).
    subroutine model_tangent(me, t, y, mass, stiffness, damping, stat, errmsg)
        class(model_ode_t), intent(inout) :: me
        real(wp), intent(in) :: t                      !! time [s]
        real(wp), intent(in) :: y(:)                   !! state (x_F, xdot_F, s, E)
        real(wp), intent(out) :: mass(:, :)            !! (nfree, nfree) a_FF [kg, kg m, kg m^2]
        real(wp), intent(out) :: stiffness(:, :)       !! (nfree, nfree) K_FF of the elements
        real(wp), intent(out) :: damping(:, :)         !! (nfree, nfree) C_FF of the elements
        integer, intent(out) :: stat                   !! stat_ok
        character(len=msglen), intent(out) :: errmsg   !! ''
        real(wp) :: kgen(me%ws%ndof, me%ws%ndof), cgen(me%ws%ndof, me%ws%ndof)
        integer :: nf
        nf = me%ws%nfree
        stat = stat_ok
        errmsg = ''
        call set_element_states(me%model, me%ws, y)
        associate (model => me%model, ws => me%ws)
            call state_to_coordinates(model, ws, t, y(1:nf), y(nf + 1:2*nf))
            call body_kinematics(model%tree, ws%x, ws%xd, ws%kin)
            call composite_rigid_body(model%tree, ws%kin, ws%a)
            call generalized_tangent(model, ws%kin, t, ws%x, ws%xd, kgen, cgen)
            call free_block(ws, ws%a, mass)
            call free_block(ws, kgen, stiffness)
            call free_block(ws, cgen, damping)
        end associate
    end subroutine model_tangent

    !> y = (x_F, xdot_F, s, E) -> y' = (xdot_F, xddot_F, sdot, energy-audit
    !! powers); sdot of a family switched off is zero.
    subroutine model_rhs(me, t, y, dydt, stat, errmsg)
        class(model_ode_t), intent(inout) :: me
        real(wp), intent(in) :: t                      !! time [s]
        real(wp), intent(in) :: y(:)                   !! state (x_F, xdot_F, s, E)
        real(wp), intent(out) :: dydt(:)               !! (xdot_F, xddot_F, sdot, energy-audit powers [W])
        integer, intent(out) :: stat                   !! stat_ok, or the failure of dynamics_evaluate
        character(len=msglen), intent(out) :: errmsg   !! what failed, at what time ('' when stat_ok)
        integer :: nf, ns, f, i0, n
        nf = me%ws%nfree
        ns = me%ws%nstate
        me%nevals = me%nevals + 1
        call set_element_states(me%model, me%ws, y)
        dydt(1:nf) = y(nf + 1:2*nf)
        call dynamics_evaluate(me%model, me%ws, t, y(1:nf), y(nf + 1:2*nf), dydt(nf + 1:2*nf), stat, errmsg)
        if (ns > 0) then
            dydt(2*nf + 1:2*nf + ns) = zero
            do f = 1, size(me%model%family)
                n = me%model%family(f)%f%state_count()
                if (n == 0 .or. .not. me%model%family_on(f)) cycle
                i0 = 2*nf + me%ws%state_first(f)
                call me%model%family(f)%f%state_rates(t, me%ws%kin, y(i0 + 1:i0 + n), dydt(i0 + 1:i0 + n))
            end do
        end if
        dydt(2*nf + ns + 1:2*nf + ns + nenergy) = [me%ws%eo%energy%p_diss, me%ws%eo%energy%p_muscle, me%ws%eo%p_applied, &
                                                   me%ws%p_prescribed]
    end subroutine model_rhs

end module hn_dynamics
