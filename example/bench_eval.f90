!> Benchmark (not a test): wall time of one dynamics evaluation --
!! kinematics, loads, a_ij, f_i and the solve -- for the full 54-DOF
!! head/neck model and for random open trees of 9, 18, 36 and 72 bodies
!! (6 DOF each), on the three solver paths: GAUSS (the paper's: partial
!! velocities, eq 17, eq 18, Gaussian elimination), CHOLESKY (composite
!! rigid body a_ij, recursive f_i, Cholesky; the default) and ABA
!! (articulated-body algorithm, O(n)). Median of many calls; ratios are
!! measured in the same run. Also the structured Jacobian (element
!! tangents and a_ij) against one evaluation.
!!
!!   fpm run --example bench_eval --profile release
program bench_eval
    use hn_kinds, only: wp, i8, msglen, zero
    use hn_tree, only: body_tree_t, tree_allocate, tree_build
    use hn_model, only: model_t, model_init
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_dynamics, only: dyn_workspace_t, dynamics_setup, dynamics_evaluate
    use hn_linsolve, only: solver_gauss, solver_cholesky, solver_articulated
    use hn_random, only: rng_t
    use hn_sorting, only: sort_index
    use hn_ode, only: ode_system_t
    use hn_dynamics, only: model_ode_t, model_ode_init, state_size, coordinates_to_state
    implicit none
    integer, parameter :: sizes(4) = [9, 18, 36, 72]
    type(case_t) :: cs
    integer :: stat, k
    character(len=msglen) :: msg
    real(wp) :: tg, tc, ta, t9(3), tj

    write (*, '(a)') 'one dynamics evaluation (kinematics + loads + a_ij + f_i + solve), median [us]'
    call read_case('input/nbdl15g.inp', 'input/nbdl15g.inp', cs, stat, msg)
    if (stat /= 0) error stop trim(msg)
    tg = time_eval(cs%model, solver_gauss, cs%x0)
    tc = time_eval(cs%model, solver_cholesky, cs%x0)
    ta = time_eval(cs%model, solver_articulated, cs%x0)
    tj = time_tangent(cs%model, cs%x0)
    write (*, '(a,i3,a,i3,a)') 'head/neck model (nbdl15g.inp): ', cs%model%tree%ndof, ' DOF, ', &
        count(.not. cs%model%prescribed), ' free, every element'
    write (*, '(a,f9.2,a,f9.2,a,f9.2,a)') '  GAUSS ', tg, '   CHOLESKY ', tc, '   ABA ', ta, ' us'
    write (*, '(a,f6.3,a,f6.3)') '  CHOLESKY / GAUSS ', tc/tg, '   ABA / GAUSS ', ta/tg
    write (*, '(a,f9.2,a,f6.2,a)') '  structured Jacobian (a_ij, element K and C) ', tj, ' us = ', tj/tc, &
        ' CHOLESKY evaluations'
    write (*, '(a)') ''
    write (*, '(a)') ' bodies   DOF    GAUSS   CHOLESKY        ABA   growth from 9 bodies: GAUSS CHOLESKY   ABA'
    do k = 1, size(sizes)
        call random_tree_model(sizes(k), cs%model)
        tg = time_eval(cs%model, solver_gauss)
        tc = time_eval(cs%model, solver_cholesky)
        ta = time_eval(cs%model, solver_articulated)
        if (k == 1) t9 = [tg, tc, ta]
        write (*, '(i7,i6,3f11.2,18x,3f8.2)') sizes(k), 6*sizes(k), tg, tc, ta, tg/t9(1), tc/t9(2), ta/t9(3)
    end do
    write (*, '(a)') '(size ratio 72/9 = 8: n^2 = 64, n^3 = 512)'

contains

    !> Median wall time [us] of one evaluation over random states.
    real(wp) function time_eval(model, solver, xbase) result(med)
        type(model_t), intent(inout) :: model
        integer, intent(in) :: solver
        real(wp), intent(in), optional :: xbase(:)
        type(dyn_workspace_t) :: ws
        type(rng_t) :: rng
        integer, parameter :: nrep = 41
        real(wp) :: samples(nrep), r
        real(wp), allocatable :: x(:), xd(:), xdd(:)
        integer(i8) :: c0, c1, rate
        integer :: rep, inner, ninner, st, j
        character(len=msglen) :: m
        model%solver = solver
        call dynamics_setup(model, ws)
        allocate (x(ws%nfree), xd(ws%nfree), xdd(ws%nfree))
        call rng%seed(7)      ! the same states for every solver and build
        do j = 1, ws%nfree
            r = rng%uniform(0.0_wp, 1.0_wp)
            x(j) = 0.1_wp*(r - 0.5_wp)
            if (present(xbase)) x(j) = xbase(ws%ifree(j)) + 0.01_wp*(r - 0.5_wp)
            xd(j) = rng%uniform(-0.5_wp, 0.5_wp)
        end do
        call dynamics_evaluate(model, ws, 0.01_wp, x, xd, xdd, st, m)
        if (st /= 0) error stop 'bench_eval: the evaluation failed: '//trim(m)
        ninner = max(1, 20000/ws%ndof**2*10)
        do rep = 1, nrep
            call system_clock(c0, rate)
            do inner = 1, ninner
                call dynamics_evaluate(model, ws, 0.01_wp, x, xd, xdd, st, m)
            end do
            call system_clock(c1)
            samples(rep) = real(c1 - c0, wp)/real(rate, wp)/ninner*1.0e6_wp
        end do
        samples = samples(sort_index(samples))
        med = samples((nrep + 1)/2)
    end function time_eval

    !> Median wall time [us] of one structured tangent (mass, stiffness,
    !! damping of the free coordinates) near the neutral state.
    real(wp) function time_tangent(model, xbase) result(med)
        type(model_t), intent(in) :: model
        real(wp), intent(in) :: xbase(:)
        type(model_ode_t) :: sys
        integer, parameter :: nrep = 21, ninner = 20
        real(wp), allocatable :: y(:), mm(:, :), kk(:, :), cc(:, :)
        real(wp) :: samples(nrep)
        integer(i8) :: c0, c1, rate
        integer :: rep, inner, st, nf
        character(len=msglen) :: m
        call model_ode_init(sys, model)
        nf = sys%ws%nfree
        allocate (y(state_size(sys)), mm(nf, nf), kk(nf, nf), cc(nf, nf))
        call coordinates_to_state(sys%ws, xbase, 0*xbase, y)
        do rep = 1, nrep
            call system_clock(c0, rate)
            do inner = 1, ninner
                call sys%second_order_tangent(0.01_wp, y, mm, kk, cc, st, m)
            end do
            call system_clock(c1)
            samples(rep) = real(c1 - c0, wp)/real(rate, wp)/ninner*1.0e6_wp
        end do
        samples = samples(sort_index(samples))
        med = samples((nrep + 1)/2)
    end function time_tangent


    !> A random tree of nb bodies, all 6 coordinates active, gravity only.
    subroutine random_tree_model(nb, model)
        integer, intent(in) :: nb
        type(model_t), intent(out) :: model
        type(body_tree_t) :: tree
        integer :: k, st
        real(wp) :: r(8)
        character(len=msglen) :: m
        call tree_allocate(tree, nb)
        do k = 1, nb
            call random_number(r)
            tree%parent(k) = merge(0, max(1, k - 1 - int(3*r(1))), k == 1)
            tree%mass(k) = 0.3_wp + r(2)
            tree%inertia(:, :, k) = zero
            tree%inertia(1, 1, k) = 1.0e-3_wp*(1 + r(3))
            tree%inertia(2, 2, k) = 1.0e-3_wp*(1 + r(4))
            tree%inertia(3, 3, k) = 1.0e-3_wp*(1 + r(5))
            tree%joint_parent(:, k) = [0.0_wp, 0.0_wp, 0.01_wp + 0.01_wp*r(6)]
            tree%joint_child(:, k) = [0.0_wp, 0.0_wp, -0.01_wp - 0.01_wp*r(7)]
        end do
        call tree_build(tree, st, m)
        call model_init(model, tree)
    end subroutine random_tree_model

end program bench_eval
