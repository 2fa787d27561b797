!> The settled start (HOLD PRESTRAIN): a specimen stands in its measured
!! posture because its joints are strained by the weight above them. The
!! model stands in its start posture x0 when the elastic neutral of the
!! joints' own deformable elements (the discs' references and the
!! neutral-zone springs' neutral values; every family's `prestrain`) is
!! displaced by dx, found so that the free accelerations vanish at the
!! start state:
!!
!!   r(dx) = -a_FF xddot_F(t0, x0, xd0; dx) = 0,
!!
!! r the generalized forces a holding support would have to add (HOLD
!! POSTURE's q_hold), solved by Newton's method with a forward-difference
!! Jacobian J = dr/d(dx_F) over the free coordinates and a halving line
!! search. At the start it equals HOLD POSTURE (the same accelerations);
!! as the joints turn, the pre-strained elements follow their own laws
!! (the sinh of a neutral-zone spring stiffens from its strained point),
!! where HOLD POSTURE's forces stay constant. Line elements keep their free
!! lengths and range elements their ranges: they are anatomical geometry,
!! not the joint's elastic neutral.
module hn_prestrain
    use hn_kinds, only: wp, zero, one, half, msglen
    use hn_status, only: stat_ok, stat_singular, stat_bad_model
    use hn_tree, only: dof_label
    use hn_kinematics, only: kinematics_t, kinematics_allocate, partial_velocities
    use hn_model, only: model_t, neutral_coordinates
    use hn_dynamics, only: model_ode_t, model_ode_init, coordinates_to_state, inertia_forces_free, state_size
    use hn_lapack, only: dgetrf, dgetrs
    implicit none
    private

    public :: prestrain_t, prestrain_model, settle_prestrain

    integer, parameter :: max_newton = 30          !! Newton iterations before giving up
    real(wp), parameter :: fd_step = 1.0e-7_wp     !! difference step of J [m, rad]
    real(wp), parameter :: rel_tol = 1.0e-10_wp    !! converged: max |r| <= rel_tol max |r(0)| (or abs_tol)
    real(wp), parameter :: abs_tol = 1.0e-12_wp    !! [N, N m]
    real(wp), parameter :: carried = 1.0e-9_wp     !! a column of J below this share of the largest: no element carries it

    !> The pre-strain that settles a start posture.
    type :: prestrain_t
        real(wp), allocatable :: dx(:)     !! (n) displacement of the neutral of every active coordinate [m, rad]
        real(wp) :: load = zero            !! largest generalized force r(0) the pre-strain carries [N, N m]
        real(wp) :: residual = zero        !! largest left, max |r(dx)| [N, N m]
        integer :: largest = 0             !! active coordinate of the largest rotation |dx| (0: none)
        integer :: iterations = 0          !! Newton iterations
    end type prestrain_t

contains

    !> Pre-strain a model: every family's references measured in the
    !! neutral configuration displaced by dx (each family's `prestrain`).
    pure subroutine prestrain_model(model, dx)
        type(model_t), intent(inout) :: model    !! the model, unstrained; out: pre-strained by dx
        real(wp), intent(in) :: dx(:)            !! (n) displacement of every active coordinate [m, rad]
        type(kinematics_t) :: kin
        real(wp) :: x(model%tree%ndof)
        integer :: f
        x = neutral_coordinates(model) + dx
        call kinematics_allocate(model%tree, kin)
        call partial_velocities(model%tree, x, 0*x, kin)
        do f = 1, size(model%family)
            call model%family(f)%f%prestrain(kin, dx)
        end do
    end subroutine prestrain_model

    !> Settle the start state (t, x, xd): the pre-strain dx with r(dx) = 0
    !! (module doc), and the model pre-strained by it. Fails (stat_bad_model)
    !! when a free coordinate's load is carried by no pre-strainable element
    !! or Newton's method does not converge; the model is then unchanged.
    subroutine settle_prestrain(model, t, x, xd, ps, stat, errmsg)
        type(model_t), intent(inout) :: model        !! the model, unstrained; out: pre-strained
        real(wp), intent(in) :: t                    !! start time [s]
        real(wp), intent(in) :: x(:)                 !! all active coordinates at the start [m, rad]
        real(wp), intent(in) :: xd(:)                !! their rates [m/s, rad/s]
        type(prestrain_t), intent(out) :: ps         !! the pre-strain
        integer, intent(out) :: stat                 !! stat_ok, stat_bad_model, or a dynamics evaluation's failure
        character(len=msglen), intent(out) :: errmsg !! what failed
        type(model_ode_t) :: sys
        real(wp), allocatable :: y(:), dxf(:), r(:), rt(:), step(:), jac(:, :), cn(:)
        integer, allocatable :: ipiv(:)
        real(wp) :: tol, lam
        integer :: nf, j, it, info
        logical :: better
        call model_ode_init(sys, model)
        nf = sys%ws%nfree
        allocate (y(state_size(sys)), dxf(nf), r(nf), rt(nf), step(nf), jac(nf, nf), cn(nf), ipiv(nf))
        call coordinates_to_state(sys%ws, x, xd, y)
        dxf = zero
        call residual(dxf, r, stat, errmsg)
        if (stat /= stat_ok) return
        ps%load = max(maxval(abs(r)), zero)
        tol = max(rel_tol*ps%load, abs_tol)
        do it = 1, max_newton
            if (max(maxval(abs(r)), zero) <= tol) exit
            ps%iterations = it
            do j = 1, nf
                step = dxf
                step(j) = step(j) + fd_step
                call residual(step, rt, stat, errmsg)
                if (stat /= stat_ok) return
                jac(:, j) = (rt - r)/fd_step
            end do
            cn = maxval(abs(jac), dim=1)
            do j = 1, nf
                if (cn(j) > carried*maxval(cn)) cycle
                stat = stat_bad_model
                errmsg = 'coordinate '//trim(dof_label(model%tree, sys%ws%ifree(j)))// &
                         ' is carried by no disc or neutral-zone spring: its load cannot be a pre-strain'
                return
            end do
            step = -r
            call dgetrf(nf, nf, jac, nf, ipiv, info)
            if (info == 0) call dgetrs('N', nf, 1, jac, nf, ipiv, step, nf, info)
            if (info /= 0) then
                stat = stat_singular
                errmsg = 'the pre-strain Jacobian is singular'
                return
            end if
            lam = one
            better = .false.
            do while (lam >= one/64)
                call residual(dxf + lam*step, rt, stat, errmsg)
                if (stat /= stat_ok) return
                better = norm2(rt) < norm2(r)
                if (better) exit
                lam = half*lam
            end do
            if (.not. better) exit
            dxf = dxf + lam*step
            r = rt
        end do
        ps%residual = max(maxval(abs(r)), zero)
        if (ps%residual > tol) then
            stat = stat_bad_model
            write (errmsg, '(a,i0,a,es10.3,a,es10.3,a)') 'no pre-strain settles the start posture: after ', ps%iterations, &
                ' Newton iterations ', ps%residual, ' N or N m is left of ', ps%load
            return
        end if
        allocate (ps%dx(model%tree%ndof))
        ps%dx = zero
        ps%dx(sys%ws%ifree) = dxf
        do j = 1, model%tree%ndof
            if (model%tree%dof_local(j) < 4) cycle
            if (ps%largest == 0) then
                ps%largest = j
            else if (abs(ps%dx(j)) > abs(ps%dx(ps%largest))) then
                ps%largest = j
            end if
        end do
        call prestrain_model(model, ps%dx)

    contains

        !> r(dx_F): the generalized forces still to be held with the model
        !! pre-strained by dx_F (the free coordinates').
        subroutine residual(dxfree, rr, st, msg)
            real(wp), intent(in) :: dxfree(:)
            real(wp), intent(out) :: rr(:)
            integer, intent(out) :: st
            character(len=msglen), intent(out) :: msg
            real(wp) :: dfull(model%tree%ndof), g(size(y))
            dfull = zero
            dfull(sys%ws%ifree) = dxfree
            sys%model = model
            call prestrain_model(sys%model, dfull)
            call sys%rhs(t, y, g, st, msg)
            if (st /= stat_ok) return
            rr = -inertia_forces_free(sys%model, sys%ws, g(nf + 1:2*nf))
        end subroutine residual

    end subroutine settle_prestrain

end module hn_prestrain
