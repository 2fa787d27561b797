!> The hot path allocates nothing: runs N + 1 dynamics evaluations on one
!! solver path (GAUSS, CHOLESKY or ABA) or N + 1 structured Jacobians
!! (JACOBIAN) of the shipped NBDL 15 g model at a fixed state, every
!! workspace set up before. test/scripts/hot_path_allocations.sh counts the
!! program's heap allocations (malloc, calloc, realloc through LD_PRELOAD)
!! for two values of N: the counts must be the same.
!!     fpm run --profile release --example hot_path_allocations -- PATH N
program hot_path_allocations
    use hn_kinds, only: wp, msglen
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_dynamics, only: dyn_workspace_t, dynamics_setup, dynamics_evaluate, model_ode_t, model_ode_init, &
                           state_size, coordinates_to_state
    use hn_linsolve, only: solver_gauss, solver_cholesky, solver_articulated
    implicit none
    type(case_t) :: cs
    integer :: stat, n, k, s, nf
    character(len=msglen) :: msg
    character(len=32) :: arg, path
    integer, parameter :: solvers(3) = [solver_gauss, solver_cholesky, solver_articulated]
    type(dyn_workspace_t) :: ws(3)
    type(model_ode_t) :: sys
    real(wp), allocatable :: x(:, :), xd(:, :), xdd(:, :), y(:), mm(:, :), kk(:, :), cc(:, :)

    call get_command_argument(1, path)
    call get_command_argument(2, arg)
    read (arg, *, iostat=stat) n
    if (stat /= 0 .or. n < 0 .or. all(path /= [character(len=32) :: 'GAUSS', 'CHOLESKY', 'ABA', 'JACOBIAN'])) then
        write (*, '(a)') 'usage: hot_path_allocations GAUSS|CHOLESKY|ABA|JACOBIAN N   (N >= 0)'
        error stop 2
    end if
    call read_case('input/nbdl15g.inp', 'input/nbdl15g.inp', cs, stat, msg)
    if (stat /= 0) then
        write (*, '(a)') trim(msg)
        error stop 1
    end if
    ! every workspace and array first: what is allocated once is not the hot path
    do s = 1, size(solvers)
        cs%model%solver = solvers(s)
        call dynamics_setup(cs%model, ws(s))
    end do
    nf = ws(1)%nfree
    allocate (x(nf, 3), xd(nf, 3), xdd(nf, 3))
    do s = 1, size(solvers)
        x(:, s) = cs%x0(ws(s)%ifree)
        xd(:, s) = 0.1_wp
    end do
    call model_ode_init(sys, cs%model)
    allocate (y(state_size(sys)), mm(nf, nf), kk(nf, nf), cc(nf, nf))
    call coordinates_to_state(sys%ws, cs%x0, 0*cs%x0, y)
    xdd = 0; kk = 0
    s = findloc([character(len=32) :: 'GAUSS', 'CHOLESKY', 'ABA'], path, dim=1)
    do k = 0, n
        if (s > 0) then
            cs%model%solver = solvers(s)
            call dynamics_evaluate(cs%model, ws(s), 0.05_wp, x(:, s), xd(:, s), xdd(:, s), stat, msg)
        else
            call sys%second_order_tangent(0.05_wp, y, mm, kk, cc, stat, msg)
        end if
        if (stat /= 0) then
            write (*, '(a)') trim(msg)
            error stop 1
        end if
    end do
    write (*, '(3a,i0,a,es12.5)') 'path ', trim(path), ', ', n + 1, ' calls, checksum ', sum(xdd) + sum(kk)
end program hot_path_allocations
