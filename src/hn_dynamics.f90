!> One dynamics evaluation: prescribed motions, kinematics, loads, a_ij and
!! f_i, the partition into free and prescribed coordinates, and the solve
!! a_FF xddot_F = f_F - a_FP xddot_P. Also the model as an ODE system
!! y = (x_F, xdot_F) for the integrators.
module hn_dynamics
    use hn_kinds, only: wp, zero, msglen
    use hn_model, only: model_t
    use hn_kinematics, only: kinematics_t, kinematics_allocate, partial_velocities
    use hn_loads, only: body_loads_t, loads_allocate
    use hn_kane, only: a_ij, f_i
    use hn_forces, only: compute_loads, element_output_t, element_output_allocate
    use hn_linsolve, only: linear_solve
    use hn_motion, only: motion_eval
    use hn_ode, only: ode_system_t
    implicit none
    private

    public :: dyn_workspace_t, dynamics_setup, dynamics_evaluate, model_ode_t, model_ode_init
    public :: state_to_coordinates, coordinates_to_state

    !> Work arrays of a dynamics evaluation and the results of the last one.
    type :: dyn_workspace_t
        integer :: ndof = 0, nfree = 0, npres = 0
        integer, allocatable :: ifree(:), ipres(:)  !! free and prescribed coordinate numbers
        type(kinematics_t) :: kin
        type(body_loads_t) :: loads
        type(element_output_t) :: eo                 !! element forces of the last evaluation
        real(wp), allocatable :: x(:), xd(:), xdd(:) !! all active coordinates, rates, accelerations
        real(wp), allocatable :: a(:, :), f(:)       !! a_ij and f_i of all active coordinates
        real(wp), allocatable :: aff(:, :), bf(:)    !! the free partition and its right-hand side
    end type dyn_workspace_t

    !> The model as a first-order system for the integrators.
    type, extends(ode_system_t) :: model_ode_t
        type(model_t) :: model
        type(dyn_workspace_t) :: ws
    contains
        procedure :: rhs => model_rhs
    end type model_ode_t

contains

    !> Size the workspace for a model.
    pure subroutine dynamics_setup(model, ws)
        type(model_t), intent(in) :: model
        type(dyn_workspace_t), intent(out) :: ws
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
        call kinematics_allocate(model%tree, ws%kin)
        call loads_allocate(ws%loads, model%tree%nbody, n)
        call element_output_allocate(model, ws%eo)
        allocate (ws%x(n), ws%xd(n), ws%xdd(n), ws%a(n, n), ws%f(n))
        allocate (ws%aff(ws%nfree, ws%nfree), ws%bf(ws%nfree))
        ws%x = zero; ws%xd = zero; ws%xdd = zero
    end subroutine dynamics_setup

    !> Fill all active coordinates from the free ones and the prescribed motions at t.
    pure subroutine state_to_coordinates(model, ws, t, xf, xdf)
        type(model_t), intent(in) :: model
        type(dyn_workspace_t), intent(inout) :: ws
        real(wp), intent(in) :: t, xf(:), xdf(:)
        integer :: i, j
        ws%x(ws%ifree) = xf
        ws%xd(ws%ifree) = xdf
        do i = 1, ws%npres
            j = ws%ipres(i)
            call motion_eval(model%motion(j), t, ws%x(j), ws%xd(j), ws%xdd(j))
        end do
    end subroutine state_to_coordinates

    !> Pack the free coordinates and rates of full arrays into a state vector.
    pure subroutine coordinates_to_state(ws, x, xd, y)
        type(dyn_workspace_t), intent(in) :: ws
        real(wp), intent(in) :: x(:), xd(:)
        real(wp), intent(out) :: y(:)
        y(1:ws%nfree) = x(ws%ifree)
        y(ws%nfree + 1:2*ws%nfree) = xd(ws%ifree)
    end subroutine coordinates_to_state

    !> Accelerations of the free coordinates at (t, xf, xdf); the full
    !! kinematics, loads, a_ij, f_i and xddot stay in ws for output.
    pure subroutine dynamics_evaluate(model, ws, t, xf, xdf, xddf, stat, errmsg)
        type(model_t), intent(in) :: model
        type(dyn_workspace_t), intent(inout) :: ws
        real(wp), intent(in) :: t, xf(:), xdf(:)
        real(wp), intent(out) :: xddf(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        integer :: i

        call state_to_coordinates(model, ws, t, xf, xdf)
        call partial_velocities(model%tree, ws%x, ws%xd, ws%kin)
        call compute_loads(model, t, ws%kin, ws%x, ws%xd, ws%loads, ws%eo)
        call a_ij(model%tree, ws%kin, ws%a)
        call f_i(model%tree, ws%kin, ws%loads, ws%f)

        ws%aff = ws%a(ws%ifree, ws%ifree)
        ws%bf = ws%f(ws%ifree)
        do i = 1, ws%npres
            ws%bf = ws%bf - ws%a(ws%ifree, ws%ipres(i))*ws%xdd(ws%ipres(i))
        end do
        stat = 0
        errmsg = ''
        if (ws%nfree > 0) call linear_solve(model%solver, ws%aff, ws%bf, stat, errmsg)
        if (stat /= 0) then
            write (errmsg, '(a,es12.5,2a)') 't = ', t, ' s: ', trim(errmsg)
            xddf = zero
            return
        end if
        xddf = ws%bf
        ws%xdd(ws%ifree) = xddf
    end subroutine dynamics_evaluate

    !> Wrap a model as an ODE system.
    subroutine model_ode_init(sys, model)
        type(model_ode_t), intent(out) :: sys
        type(model_t), intent(in) :: model
        sys%model = model
        call dynamics_setup(sys%model, sys%ws)
    end subroutine model_ode_init

    !> y = (x_F, xdot_F) -> y' = (xdot_F, xddot_F).
    subroutine model_rhs(me, t, y, dydt, stat, errmsg)
        class(model_ode_t), intent(inout) :: me
        real(wp), intent(in) :: t
        real(wp), intent(in) :: y(:)
        real(wp), intent(out) :: dydt(:)
        integer, intent(out) :: stat
        character(len=msglen), intent(out) :: errmsg
        integer :: nf
        nf = me%ws%nfree
        me%nevals = me%nevals + 1
        dydt(1:nf) = y(nf + 1:2*nf)
        call dynamics_evaluate(me%model, me%ws, t, y(1:nf), y(nf + 1:2*nf), dydt(nf + 1:2*nf), stat, errmsg)
    end subroutine model_rhs

end module hn_dynamics
