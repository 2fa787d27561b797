!> The iteration matrix W = I - hg J of the linearly implicit (Rosenbrock)
!! methods: the Jacobian J of y' = g(t, y), the factorization of W for one
!! value of hg, and solves W u = r. Three forms, by what the system offers:
!!   dense          J by forward differences, W (n x n) by LU;
!!   second order   y = (x, xdot, quadratures), J = [0 I; J21 J22] with
!!                  J21, J22 by forward differences: only the m x m matrix
!!                  I - hg J22 - hg^2 J21 is factored (LU);
!!   tangent        the same structure with J21 = -M^-1 K, J22 = -M^-1 C
!!                  from the system's mass, stiffness and damping: the
!!                  symmetric m x m matrix M + hg C + hg^2 K is factored
!!                  (Cholesky; LU when it is not positive definite).
!! In the second-order forms u_x = r_x + hg u_v, the quadrature rows of J
!! are taken as zero (W = I there). Components between the rates and the
!! quadratures (first-order states of the system, such as the muscles'
!! activations: y = (x, xdot, s, quadratures)) get the diagonal of their
!! own block, d = d(sdot_i)/ds_i by one forward difference with every s
!! moved at once (exact when each rate depends on its own state alone),
!! and the blocks coupling them with x and xdot are dropped: W = 1 - hg d
!! there. ROS34PW2 is a W-method: it keeps its order with any
!! approximation of J, and the stiffness of an activation (1/T, up to
!! 1/tau_act) is treated implicitly. The dense form (ROS2's Jacobian, FD)
!! differentiates every column but the quadratures, the states included. J and the factorization are
!! kept until the method asks for new ones.
module hn_iteration_matrix
    use hn_kinds, only: wp, zero, one, msglen
    use hn_status, only: stat_ok, stat_singular
    use hn_ode, only: ode_system_t
    use hn_lapack, only: dgetrf, dgetrs
    use hn_linsolve, only: cholesky_factor, cholesky_substitute
    implicit none
    private

    public :: iteration_matrix_t, fd_jacobian

    integer, parameter :: form_dense = 1, form_second_fd = 2, form_tangent = 3

    !> Relative difference step of the finite-difference Jacobians, and the
    !! smallest absolute step (for components near zero).
    real(wp), parameter :: fd_step_rel = sqrt(epsilon(one)), fd_step_floor = 1.0e-4_wp
    !> Step of central differences: relative, and its floor in |y| [m, rad, m/s, rad/s]
    real(wp), parameter :: central_step_rel = 1.0e-7_wp, central_step_floor = one

    !> Jacobian, factorization and counts.
    type :: iteration_matrix_t
        private
        integer :: form = 0
        integer :: n = 0, m = 0
        real(wp), allocatable :: jac(:, :)      !! dense: J (n,n); second order: [J21 J22] (m,2m)
        real(wp), allocatable :: mass(:, :), stiff(:, :), damp(:, :)  !! tangent form (m,m)
        real(wp), allocatable :: sdiag(:)       !! second-order forms: d(sdot)/ds of the first-order states
        real(wp), allocatable :: fac(:, :)      !! the factored matrix
        integer, allocatable :: ipiv(:)
        logical :: cholesky = .false.           !! fac holds a Cholesky factor (else LU)
        logical :: have_jac = .false.
        real(wp) :: hg = -one                   !! hg of the factorization (< 0: none)
        integer :: njac = 0, nfact = 0
    contains
        procedure :: form_jacobian => im_form_jacobian
        procedure :: factor => im_factor
        procedure :: solve => im_solve
        procedure :: has_jacobian => im_has_jacobian
        procedure :: factored_for => im_factored_for
        procedure :: jacobians => im_jacobians
        procedure :: factorizations => im_factorizations
        procedure :: forget => im_forget
    end type iteration_matrix_t

contains

    !> Form J at (t, y) with f = g(t, y): from the system's tangent when it
    !! has one (unless force_differences), else by forward differences
    !! (of the second-order block only when the system is second order).
    subroutine im_form_jacobian(me, sys, t, y, f, stat, errmsg, force_differences)
        class(iteration_matrix_t), intent(inout) :: me
        class(ode_system_t), intent(inout) :: sys            !! the system y' = g(t, y)
        real(wp), intent(in) :: t                            !! time [s]
        real(wp), intent(in) :: y(:)                         !! state
        real(wp), intent(in) :: f(:)                         !! g(t, y)
        integer, intent(out) :: stat                         !! stat_ok, or the system's failure
        character(len=msglen), intent(out) :: errmsg         !! the system's message ('' when stat_ok)
        logical, intent(in), optional :: force_differences   !! dense differences whatever the system offers
        real(wp), allocatable :: full(:, :)
        logical :: dense
        integer :: m
        dense = .false.
        if (present(force_differences)) dense = force_differences
        me%n = size(y)
        m = sys%nsecond
        if (dense .or. m == 0) then
            me%form = form_dense
            me%m = 0
            if (allocated(me%jac)) deallocate (me%jac)
            allocate (me%jac(me%n, me%n))
            call fd_jacobian(sys, t, y, f, me%jac, stat, errmsg)
        else if (sys%has_tangent) then
            me%form = form_tangent
            me%m = m
            if (allocated(me%mass)) deallocate (me%mass, me%stiff, me%damp)
            allocate (me%mass(m, m), me%stiff(m, m), me%damp(m, m))
            call sys%second_order_tangent(t, y, me%mass, me%stiff, me%damp, stat, errmsg)
        else
            me%form = form_second_fd
            me%m = m
            allocate (full(me%n, me%n))
            call fd_jacobian(sys, t, y, f, full, stat, errmsg, 2*m)
            me%jac = full(m + 1:2*m, 1:2*m)
        end if
        if (stat /= stat_ok) return
        if (me%form /= form_dense) call state_diagonal(sys, t, y, f, 2*m, me%sdiag, stat, errmsg)
        if (stat /= stat_ok) return
        me%have_jac = .true.
        me%hg = -one
        me%njac = me%njac + 1
    end subroutine im_form_jacobian

    !> d(sdot_i)/ds_i of the first-order states s = y(i0 + 1:n - nquad) by
    !! one forward difference, every state moved at once.
    subroutine state_diagonal(sys, t, y, f, i0, d, stat, errmsg)
        class(ode_system_t), intent(inout) :: sys          !! the system
        real(wp), intent(in) :: t                          !! time [s]
        real(wp), intent(in) :: y(:)                       !! state
        real(wp), intent(in) :: f(:)                       !! g(t, y)
        integer, intent(in) :: i0                          !! components before the states (2 nsecond)
        real(wp), allocatable, intent(out) :: d(:)         !! the diagonal (empty without states)
        integer, intent(out) :: stat                       !! stat_ok, or the system's failure
        character(len=msglen), intent(out) :: errmsg      !! the system's message
        real(wp) :: yp(size(y)), fp(size(y)), h(size(y))
        integer :: ns
        stat = stat_ok
        errmsg = ''
        ns = size(y) - sys%nquad - i0
        allocate (d(max(ns, 0)))
        if (ns <= 0) return
        h = zero
        h(i0 + 1:i0 + ns) = fd_step_rel*max(abs(y(i0 + 1:i0 + ns)), one)
        yp = y + h
        call sys%rhs(t, yp, fp, stat, errmsg)
        if (stat /= stat_ok) return
        d = (fp(i0 + 1:i0 + ns) - f(i0 + 1:i0 + ns))/h(i0 + 1:i0 + ns)
    end subroutine state_diagonal

    !> Factor W for the given hg.
    subroutine im_factor(me, hg, stat, errmsg)
        class(iteration_matrix_t), intent(inout) :: me
        real(wp), intent(in) :: hg                     !! step times the method's gamma [s]
        integer, intent(out) :: stat                   !! stat_ok, or stat_singular (W singular)
        character(len=msglen), intent(out) :: errmsg   !! the message with hg ('' when stat_ok)
        integer :: i, k, info
        stat = stat_ok
        errmsg = ''
        k = merge(me%n, me%m, me%form == form_dense)
        if (allocated(me%fac)) then
            if (size(me%fac, 1) /= k) deallocate (me%fac, me%ipiv)
        end if
        if (.not. allocated(me%fac)) allocate (me%fac(k, k), me%ipiv(k))
        me%cholesky = .false.
        select case (me%form)
        case (form_dense)
            me%fac = -hg*me%jac
            do i = 1, k
                me%fac(i, i) = me%fac(i, i) + one
            end do
        case (form_second_fd)
            me%fac = -hg*me%jac(:, k + 1:2*k) - hg**2*me%jac(:, 1:k)
            do i = 1, k
                me%fac(i, i) = me%fac(i, i) + one
            end do
        case default
            me%fac = me%mass + hg*me%damp + hg**2*me%stiff
            call cholesky_factor(me%fac, info, i)
            me%cholesky = info == stat_ok
            if (.not. me%cholesky) me%fac = me%mass + hg*me%damp + hg**2*me%stiff
        end select
        if (.not. me%cholesky) then
            call dgetrf(k, k, me%fac, k, me%ipiv, info)
            if (info /= 0) then
                stat = stat_singular
                write (errmsg, '(a,es10.3,a)') 'the iteration matrix I - hg J is singular (hg = ', hg, ' s)'
                me%hg = -one
                return
            end if
        end if
        me%hg = hg
        me%nfact = me%nfact + 1
    end subroutine im_factor

    !> Solve W u = r in place with the factorization.
    subroutine im_solve(me, r)
        class(iteration_matrix_t), intent(in) :: me
        real(wp), intent(inout) :: r(:)      !! in: r; out: u
        real(wp) :: v(me%m)
        integer :: m, info
        m = me%m
        select case (me%form)
        case (form_dense)
            call dgetrs('N', me%n, 1, me%fac, me%n, me%ipiv, r, me%n, info)
            return
        case (form_second_fd)
            v = r(m + 1:2*m) + me%hg*matmul(me%jac(:, 1:m), r(1:m))
        case default
            v = matmul(me%mass, r(m + 1:2*m)) - me%hg*matmul(me%stiff, r(1:m))
        end select
        if (me%cholesky) then
            call cholesky_substitute(me%fac, v)
        else
            call dgetrs('N', m, 1, me%fac, m, me%ipiv, v, m, info)
        end if
        r(1:m) = r(1:m) + me%hg*v
        r(m + 1:2*m) = v
        if (size(me%sdiag) > 0) r(2*m + 1:2*m + size(me%sdiag)) = r(2*m + 1:2*m + size(me%sdiag))/(one - me%hg*me%sdiag)
    end subroutine im_solve

    !> A Jacobian has been formed.
    pure logical function im_has_jacobian(me) result(b)
        class(iteration_matrix_t), intent(in) :: me
        b = me%have_jac
    end function im_has_jacobian

    !> The factorization is of W for this hg, or with `band` for an hg0 with
    !! hg/band <= hg0 <= hg band.
    pure logical function im_factored_for(me, hg, band) result(b)
        class(iteration_matrix_t), intent(in) :: me
        real(wp), intent(in) :: hg                 !! step times the method's gamma [s]
        real(wp), intent(in), optional :: band     !! factor of the band (>= 1; default 1: hg itself)
        if (present(band)) then
            b = me%hg > zero .and. me%hg >= hg/band .and. me%hg <= hg*band
        else
            b = me%hg == hg
        end if
    end function im_factored_for

    !> Jacobians formed so far.
    pure integer function im_jacobians(me) result(k)
        class(iteration_matrix_t), intent(in) :: me
        k = me%njac
    end function im_jacobians

    !> Factorizations so far.
    pure integer function im_factorizations(me) result(k)
        class(iteration_matrix_t), intent(in) :: me
        k = me%nfact
    end function im_factorizations

    !> Drop the Jacobian (the next step forms a new one).
    pure subroutine im_forget(me)
        class(iteration_matrix_t), intent(inout) :: me
        me%have_jac = .false.
        me%hg = -one
    end subroutine im_forget

    !> Jacobian dg/dy by forward differences over the first ncol components
    !! (default: all but the quadratures; other columns zero), or by central
    !! differences when `central` (twice the evaluations, error O(h^2): the
    !! rest-mode analysis, where eigenvalues near zero decide).
    subroutine fd_jacobian(sys, t, y, f, jac, stat, errmsg, ncol, central)
        class(ode_system_t), intent(inout) :: sys      !! the system y' = g(t, y)
        real(wp), intent(in) :: t                      !! time [s]
        real(wp), intent(in) :: y(:)                   !! state
        real(wp), intent(in) :: f(:)                   !! g(t, y) (not used by central differences)
        real(wp), intent(out) :: jac(:, :)             !! (n, n) dg/dy; columns beyond ncol zero
        integer, intent(out) :: stat                   !! stat_ok, or the system's failure
        character(len=msglen), intent(out) :: errmsg   !! the system's message ('' when stat_ok)
        integer, intent(in), optional :: ncol          !! number of leading columns to form (default: n - nquad)
        logical, intent(in), optional :: central       !! central differences (default: forward)
        real(wp) :: yp(size(y)), fp(size(y)), fm(size(y)), d
        integer :: j, nc
        logical :: two_sided
        stat = stat_ok
        errmsg = ''
        nc = size(y) - sys%nquad
        if (present(ncol)) nc = ncol
        two_sided = .false.
        if (present(central)) two_sided = central
        jac = zero
        yp = y
        do j = 1, nc
            if (two_sided) then
                d = central_step_rel*max(abs(y(j)), central_step_floor)
                yp(j) = y(j) + d
                call sys%rhs(t, yp, fp, stat, errmsg)
                if (stat /= stat_ok) return
                yp(j) = y(j) - d
                call sys%rhs(t, yp, fm, stat, errmsg)
                if (stat /= stat_ok) return
                jac(:, j) = (fp - fm)/(2*d)
            else
                d = fd_step_rel*max(abs(y(j)), fd_step_floor)
                yp(j) = y(j) + d
                call sys%rhs(t, yp, fp, stat, errmsg)
                if (stat /= stat_ok) return
                jac(:, j) = (fp - f)/d
            end if
            yp(j) = y(j)
        end do
    end subroutine fd_jacobian

end module hn_iteration_matrix
