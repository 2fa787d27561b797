!> Benchmark (not a test): wall time of one dynamics evaluation --
!! kinematics, loads, a_ij, f_i and the solve -- for the full 54-DOF
!! head/neck model and for random open trees of 9, 18, 36 and 72 bodies
!! (6 DOF each), with both solvers. Median of many calls.
!!
!!   fpm run --example bench_eval --profile release
program bench_eval
    use hn_kinds, only: wp, i8, msglen, zero
    use hn_tree, only: body_tree_t, tree_allocate, tree_build
    use hn_model, only: model_t, model_init
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_dynamics, only: dyn_workspace_t, dynamics_setup, dynamics_evaluate
    use hn_linsolve, only: solver_gauss, solver_cholesky
    implicit none
    integer, parameter :: sizes(4) = [9, 18, 36, 72]
    type(case_t) :: cs
    integer :: stat, k
    character(len=msglen) :: msg
    real(wp) :: tg, tc, t9g

    write (*, '(a)') 'one dynamics evaluation (kinematics + loads + a_ij + f_i + solve), median'
    call read_case('input/nbdl15g.inp', 'input/nbdl15g.inp', cs, stat, msg)
    if (stat /= 0) error stop trim(msg)
    tg = time_eval(cs%model, solver_gauss, cs%x0)
    tc = time_eval(cs%model, solver_cholesky, cs%x0)
    write (*, '(a,i3,a,i3,a,f9.2,a,f9.2,a)') 'head/neck model (nbdl15g.inp): ', cs%model%tree%ndof, &
        ' DOF, ', count(.not. cs%model%prescribed), ' free: Gauss ', tg, ' us, Cholesky ', tc, ' us'
    write (*, '(a)') ''
    write (*, '(a)') ' bodies   DOF   Gauss (us)  Cholesky (us)  Gauss / 9-body'
    do k = 1, size(sizes)
        call random_tree_model(sizes(k), cs%model)
        tg = time_eval(cs%model, solver_gauss)
        tc = time_eval(cs%model, solver_cholesky)
        if (k == 1) t9g = tg
        write (*, '(i7,i6,f13.2,f15.2,f16.2)') sizes(k), 6*sizes(k), tg, tc, tg/t9g
    end do

contains

    !> Median wall time [us] of one evaluation over random states.
    real(wp) function time_eval(model, solver, xbase) result(med)
        type(model_t), intent(inout) :: model
        integer, intent(in) :: solver
        real(wp), intent(in), optional :: xbase(:)
        type(dyn_workspace_t) :: ws
        integer, parameter :: nrep = 41
        real(wp) :: samples(nrep), r
        real(wp), allocatable :: x(:), xd(:), xdd(:)
        integer(i8) :: c0, c1, rate
        integer :: rep, inner, ninner, st, j
        character(len=msglen) :: m
        model%solver = solver
        call dynamics_setup(model, ws)
        allocate (x(ws%nfree), xd(ws%nfree), xdd(ws%nfree))
        do j = 1, ws%nfree
            call random_number(r)
            x(j) = 0.1_wp*(r - 0.5_wp)
            if (present(xbase)) x(j) = xbase(ws%ifree(j)) + 0.01_wp*(r - 0.5_wp)
            call random_number(r)
            xd(j) = r - 0.5_wp
        end do
        ninner = max(1, 20000/ws%ndof**2*10)
        do rep = 1, nrep
            call system_clock(c0, rate)
            do inner = 1, ninner
                call dynamics_evaluate(model, ws, 0.01_wp, x, xd, xdd, st, m)
            end do
            call system_clock(c1)
            samples(rep) = real(c1 - c0, wp)/real(rate, wp)/ninner*1.0e6_wp
        end do
        call sort(samples)
        med = samples((nrep + 1)/2)
    end function time_eval

    subroutine sort(a)
        real(wp), intent(inout) :: a(:)
        integer :: i, j
        real(wp) :: v
        do i = 2, size(a)
            v = a(i)
            j = i - 1
            do while (j >= 1)
                if (a(j) <= v) exit
                a(j + 1) = a(j)
                j = j - 1
            end do
            a(j + 1) = v
        end do
    end subroutine sort

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
