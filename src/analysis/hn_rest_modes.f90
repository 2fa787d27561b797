!> Small-motion stability of a model at rest: the Jacobian of the
!! equations of motion y' = g(t, y), y = (x_F, xdot_F), at a state of
!! rest, by central differences of whole dynamics evaluations (so it holds
!! every term: the elements' tangents, their geometric stiffness, gravity
!! and the posture-holding forces), and its eigenvalues (LAPACK dgeev).
!! The rest state is stable when every eigenvalue has a negative real part.
module hn_rest_modes
    use hn_kinds, only: wp, zero, msglen
    use hn_status, only: stat_ok, stat_singular
    use hn_model, only: model_t, hold_unreleased
    use hn_dynamics, only: model_ode_t, model_ode_init, coordinates_to_state, inertia_forces_free, state_size
    use hn_lapack, only: dgeev
    use hn_iteration_matrix, only: fd_jacobian
    implicit none
    private

    public :: rest_mode_t, rest_jacobian, rest_modes

    !> One eigenvalue of the rest state and where its mode lives.
    type :: rest_mode_t
        real(wp) :: re = zero, im = zero   !! eigenvalue [1/s]
        integer :: dominant = 0           !! free coordinate (model numbering) with the largest displacement
    end type rest_mode_t

contains

    !> Jacobian J = dg/dy (2 nf x 2 nf) of the model at time t and state
    !! (x, xd) of all active coordinates, by central differences. With
    !! `hold`, the posture-holding forces are first set so that the free
    !! accelerations vanish at that state (HOLD POSTURE, as a run does) and
    !! act in full (a release time of the model is ignored: s = 1).
    subroutine rest_jacobian(model, t, x, xd, hold, jac, ifree, stat, errmsg)
        type(model_t), intent(in) :: model              !! the model
        real(wp), intent(in) :: t                       !! time [s]
        real(wp), intent(in) :: x(:)                    !! all active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)                   !! their rates [m/s, rad/s]
        logical, intent(in) :: hold                     !! hold the posture at (x, xd)
        real(wp), allocatable, intent(out) :: jac(:, :) !! (2 nf, 2 nf)
        integer, allocatable, intent(out) :: ifree(:)   !! model numbers of the free coordinates
        integer, intent(out) :: stat                    !! stat_ok, or the failure of a dynamics evaluation
        character(len=msglen), intent(out) :: errmsg    !! what failed
        type(model_ode_t) :: sys
        real(wp), allocatable :: y(:), g(:), full(:, :)
        integer :: nf
        call model_ode_init(sys, model)
        nf = sys%ws%nfree
        ifree = sys%ws%ifree
        allocate (y(state_size(sys)), g(state_size(sys)), full(state_size(sys), state_size(sys)))
        call coordinates_to_state(sys%ws, x, xd, y)
        if (hold) then
            call hold_unreleased(sys%model)   ! the held state: s = 1, whatever a release says
            call sys%rhs(t, y, g, stat, errmsg)
            if (stat /= stat_ok) return
            sys%model%q_hold(sys%ws%ifree) = sys%model%q_hold(sys%ws%ifree) - &
                                             inertia_forces_free(sys%model, sys%ws, g(nf + 1:2*nf))
        end if
        call fd_jacobian(sys, t, y, g, full, stat, errmsg, ncol=2*nf, central=.true.)
        if (stat /= stat_ok) return
        jac = full(1:2*nf, 1:2*nf)
    end subroutine rest_jacobian

    !> Eigenvalues of the Jacobian of rest_jacobian, sorted by decreasing
    !! real part, each with the free coordinate that dominates its mode.
    subroutine rest_modes(model, t, x, xd, hold, modes, stat, errmsg)
        type(model_t), intent(in) :: model                      !! the model
        real(wp), intent(in) :: t                               !! time [s]
        real(wp), intent(in) :: x(:)                            !! all active coordinates [m, rad]
        real(wp), intent(in) :: xd(:)                           !! their rates [m/s, rad/s]
        logical, intent(in) :: hold                             !! hold the posture at (x, xd)
        type(rest_mode_t), allocatable, intent(out) :: modes(:) !! (2 nf) eigenvalues, largest real part first
        integer, intent(out) :: stat                            !! stat_ok; stat_singular when dgeev fails
        character(len=msglen), intent(out) :: errmsg            !! what failed
        real(wp), allocatable :: jac(:, :), wr(:), wi(:), vr(:, :), work(:), mag(:)
        real(wp) :: vl(1, 1), wq(1)
        integer, allocatable :: ifree(:)
        integer :: n, nf, info, k, i
        call rest_jacobian(model, t, x, xd, hold, jac, ifree, stat, errmsg)
        if (stat /= stat_ok) return
        n = size(jac, 1)
        nf = n/2
        allocate (wr(n), wi(n), vr(n, n), modes(n), mag(nf))
        call dgeev('N', 'V', n, jac, n, wr, wi, vl, 1, vr, n, wq, -1, info)
        allocate (work(max(1, int(wq(1)))))
        call dgeev('N', 'V', n, jac, n, wr, wi, vl, 1, vr, n, work, size(work), info)
        if (info /= 0) then
            stat = stat_singular
            write (errmsg, '(a,i0)') 'dgeev did not converge: info = ', info
            return
        end if
        k = 1
        do while (k <= n)
            ! a complex pair is stored as columns k (real part) and k+1 (imaginary part)
            if (wi(k) /= zero .and. k < n) then
                mag = abs(vr(1:nf, k)) + abs(vr(1:nf, k + 1))
                modes(k) = rest_mode_t(wr(k), wi(k), ifree(maxloc(mag, dim=1)))
                modes(k + 1) = rest_mode_t(wr(k + 1), wi(k + 1), ifree(maxloc(mag, dim=1)))
                k = k + 2
            else
                mag = abs(vr(1:nf, k))
                modes(k) = rest_mode_t(wr(k), wi(k), ifree(maxloc(mag, dim=1)))
                k = k + 1
            end if
        end do
        do i = 2, n                    ! insertion sort by decreasing real part
            k = i
            do while (k > 1)
                if (modes(k - 1)%re >= modes(k)%re) exit
                modes([k - 1, k]) = modes([k, k - 1])
                k = k - 1
            end do
        end do
    end subroutine rest_modes

end module hn_rest_modes
