!> The HDF5 dump of a run with all six coordinates of every body free:
!! read back from the file, every body satisfies Newton-Euler,
!! m a = F and I alpha + omega x I omega = M, with the dumped numbers.
program test_dump_newton_euler
    use hn_kinds, only: wp, zero, one, msglen
    use hn_tree, only: body_tree_t
    use hn_model, only: model_t, model_init
    use hn_dynamics, only: model_ode_t, model_ode_init
    use hn_integrators, only: dopri5_t
    use hn_applied, only: applied_force, applied_couple, frame_body, frame_inertial
    use hn_tables, only: table_set
    use hn_h5, only: h5_file_t, h5_read_real, h5_dims
    use hn_dump, only: dump_open, dump_record
    use hn_rotation, only: cross
    use hn_testing, only: test_suite_t
    use hn_test_models, only: rng_t, random_tree
    implicit none

    integer, parameter :: nb = 9, ntimes = 4
    character(len=*), parameter :: fname = 'test_dump_newton_euler.h5'
    type(test_suite_t) :: suite
    type(rng_t) :: rng
    type(body_tree_t) :: tree
    type(model_t) :: model
    type(model_ode_t) :: sys
    type(dopri5_t) :: integ
    type(h5_file_t) :: h5
    real(wp), allocatable :: y(:), dydt(:)
    real(wp) :: t
    integer :: n, i, e, stat
    character(len=msglen) :: msg

    call random_tree(tree, nb, rng)
    call model_init(model, tree)
    deallocate (model%springs, model%applied)
    allocate (model%springs(5), model%applied(2))
    do e = 1, 5
        model%springs(e)%body_a = e - 1
        model%springs(e)%body_b = e + 4
        model%springs(e)%point_a = [0.01_wp*e, -0.02_wp, 0.03_wp]
        model%springs(e)%point_b = [-0.02_wp, 0.01_wp*e, 0.02_wp]
        model%springs(e)%length0 = 0.03_wp
        model%springs(e)%stiffness = 800.0_wp
        model%springs(e)%damping = 2.0_wp
    end do
    model%applied(1)%body = 9
    model%applied(1)%kind = applied_force
    model%applied(1)%frame = frame_body
    model%applied(1)%point = [0.05_wp, 0.0_wp, 0.04_wp]
    model%applied(1)%direction = [-1.0_wp, 0.0_wp, 0.0_wp]
    call table_set(model%applied(1)%magnitude, [zero, 0.02_wp, 0.04_wp], [zero, 300.0_wp, zero], stat)
    model%applied(2)%body = 4
    model%applied(2)%kind = applied_couple
    model%applied(2)%frame = frame_inertial
    model%applied(2)%direction = [0.0_wp, 1.0_wp, 0.0_wp]
    call table_set(model%applied(2)%magnitude, [zero, 0.1_wp], [5.0_wp, -5.0_wp], stat)
    call model_ode_init(sys, model)
    n = tree%ndof
    allocate (y(2*n + 4), dydt(2*n + 4))
    y = zero
    do i = 1, 2*n
        y(i) = merge(rng%uniform(-0.3_wp, 0.3_wp), rng%uniform(-2.0_wp, 2.0_wp), i <= n)
    end do

    call h5%create(fname, stat, msg)
    call dump_open(h5, sys%model)
    call integ%set_tolerances(1.0e-8_wp, 1.0e-10_wp); call integ%set_step(1.0e-4_wp)
    t = zero
    call integ%init(sys, t, y, stat, msg)
    do i = 1, ntimes
        if (i > 1) then
            t = t + 0.01_wp
            call integ%advance(sys, t, y, huge(one), stat, msg)
        end if
        call sys%rhs(t, y, dydt, stat, msg)
        call dump_record(h5, sys%model, sys%ws, t, stat, msg)
    end do
    call h5%close(.true., stat, msg)

    call test_dump_shapes()
    call test_newton_force_balance()
    call test_euler_moment_balance()
    call test_xdd_solves_a_f()
    call suite%finish()

contains

    subroutine test_dump_shapes()
        integer, allocatable :: d1(:), d2(:)
        integer :: s1, s2
        call h5_dims(fname, '/dump/rotation', d1, s1)
        call h5_dims(fname, '/dump/a', d2, s2)
        call suite%check(s1 == 0 .and. s2 == 0 .and. all(d1 == [3, 3, nb, ntimes]) .and. &
                         all(d2 == [n, n, ntimes]), 'dump datasets have the documented shapes')
    end subroutine test_dump_shapes

    subroutine test_newton_force_balance()
        real(wp) :: mass(nb), acc(3, nb, ntimes), force(3, nb, ntimes), err, scale
        integer :: k, it, s
        call h5_read_real(fname, '/dump/mass', mass, s)
        call h5_read_real(fname, '/dump/acceleration', acc, s)
        call h5_read_real(fname, '/dump/force', force, s)
        err = zero; scale = maxval(abs(force))
        do it = 1, ntimes
            do k = 1, nb
                err = max(err, maxval(abs(mass(k)*acc(:, k, it) - force(:, k, it))))
            end do
        end do
        call suite%near(err/scale, zero, 1.0e-11_wp, 'every dumped body: m a = F (read back from HDF5)')
    end subroutine test_newton_force_balance

    subroutine test_euler_moment_balance()
        real(wp) :: inertia(3, 3, nb), rot(3, 3, nb, ntimes), om(3, nb, ntimes), al(3, nb, ntimes)
        real(wp) :: mom(3, nb, ntimes), ir(3, 3), err, scale
        integer :: k, it, s
        call h5_read_real(fname, '/dump/inertia', inertia, s)
        call h5_read_real(fname, '/dump/rotation', rot, s)
        call h5_read_real(fname, '/dump/angular_velocity', om, s)
        call h5_read_real(fname, '/dump/angular_acceleration', al, s)
        call h5_read_real(fname, '/dump/moment', mom, s)
        err = zero; scale = maxval(abs(mom))
        do it = 1, ntimes
            do k = 1, nb
                ir = matmul(rot(:, :, k, it), matmul(inertia(:, :, k), transpose(rot(:, :, k, it))))
                err = max(err, maxval(abs(matmul(ir, al(:, k, it)) &
                                          + cross(om(:, k, it), matmul(ir, om(:, k, it))) - mom(:, k, it))))
            end do
        end do
        call suite%near(err/scale, zero, 1.0e-11_wp, &
                        'every dumped body: I alpha + omega x I omega = M (read back from HDF5)')
    end subroutine test_euler_moment_balance

    subroutine test_xdd_solves_a_f()
        real(wp) :: a(n, n, ntimes), f(n, ntimes), xdd(n, ntimes), err
        integer :: it, s
        call h5_read_real(fname, '/dump/a', a, s)
        call h5_read_real(fname, '/dump/f', f, s)
        call h5_read_real(fname, '/dump/xdd', xdd, s)
        err = zero
        do it = 1, ntimes
            err = max(err, maxval(abs(matmul(a(:, :, it), xdd(:, it)) - f(:, it)))/maxval(abs(f(:, it))))
        end do
        call suite%near(err, zero, 1.0e-9_wp, 'dumped a_ij xdd_j = f_i')
        open (newunit=s, file=fname, status='old')
        close (s, status='delete')
    end subroutine test_xdd_solves_a_f

end program test_dump_newton_euler
