!> Benchmark (not a test): what one head-plane contact costs per dynamics
!! evaluation of the 54-DOF head/neck model (input/nbdl15g.inp): the median
!! wall time of one evaluation (the least of five alternating rounds) without the contact and with a head
!! ellipsoid (semi-axes 0.10, 0.08, 0.10 m on the head's axes) pressed
!! 10 mm into a plane of R behind it (loading table 1E5 N/m, damping
!! 100 N s/m, mu 0.3), near the deck's start.
!!
!!   fpm run --example bench_contact --profile release
program bench_contact
    use hn_kinds, only: wp, i8, msglen, zero, one
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_model, only: model_t
    use hn_families, only: family_index
    use hn_tables, only: table_t
    use hn_kinematics, only: kinematics_t, kinematics_allocate, body_kinematics
    use hn_contact_geometry, only: contact_t, contact_state_t, contact_geometry
    use hn_contact_family, only: contact_family_t
    use hn_dynamics, only: dyn_workspace_t, dynamics_setup, dynamics_evaluate
    use hn_random, only: rng_t
    use hn_sorting, only: sort_index
    implicit none
    type(case_t) :: cs
    type(kinematics_t) :: kin
    type(contact_state_t) :: g
    type(contact_t) :: c
    type(table_t) :: tab
    integer :: stat
    character(len=msglen) :: msg
    real(wp) :: t_without, t_with
    type(model_t) :: plain
    type(dyn_workspace_t) :: ws
    real(wp), allocatable :: xdd(:)
    integer :: round

    call read_case('input/nbdl15g.inp', 'input/nbdl15g.inp', cs, stat, msg)
    if (stat /= 0) error stop trim(msg)
    plain = cs%model
    ! the head ellipsoid against a plane of R facing +x, 10 mm deep at the start
    c = contact_t(name='HEADREST', body=cs%head, plane_body=0, semi=[0.10_wp, 0.08_wp, 0.10_wp], &
                  normal=[one, zero, zero], load=1, damping=100.0_wp, mu=0.3_wp)
    call kinematics_allocate(cs%model%tree, kin)
    call body_kinematics(cs%model%tree, cs%x0, 0*cs%x0, kin)
    call contact_geometry(kin, c, g)
    c%point = (0.01_wp - g%depth)*c%normal
    tab%t = [zero, 0.1_wp]
    tab%y = [zero, 1.0e4_wp]
    deallocate (cs%model%family(family_index('CONTACTS'))%f)
    allocate (cs%model%family(family_index('CONTACTS'))%f, source=contact_family_t(items=[c], tables=[tab]))
    ! alternate the two on a shared machine; the least median of five rounds each
    t_without = huge(one); t_with = huge(one)
    do round = 1, 5
        t_without = min(t_without, time_eval(plain, cs%x0))
        t_with = min(t_with, time_eval(cs%model, cs%x0))
    end do
    call dynamics_setup(cs%model, ws)
    xdd = cs%x0(ws%ifree)
    call dynamics_evaluate(cs%model, ws, 0.01_wp, cs%x0(ws%ifree), 0*xdd, xdd, stat, msg)
    write (*, '(a,f8.1,a)') 'the contact at the start: normal force ', &
        ws%eo%fam(family_index('CONTACTS'))%v(1, 1), ' N'
    write (*, '(a)') 'one dynamics evaluation of nbdl15g.inp (CHOLESKY), least median of five rounds [us]'
    write (*, '(a,f9.2,a,f9.2,a,f6.2,a)') '  without contact ', t_without, '   with a head-plane contact ', t_with, &
        '   (', t_with - t_without, ' us)'

contains

    !> Median wall time [us] of one evaluation at states near xbase.
    real(wp) function time_eval(model, xbase) result(med)
        type(model_t), intent(inout) :: model
        real(wp), intent(in) :: xbase(:)
        type(dyn_workspace_t) :: ws
        type(rng_t) :: rng
        integer, parameter :: nrep = 41, ninner = 200
        real(wp) :: samples(nrep), r
        real(wp), allocatable :: x(:), xd(:), xdd(:)
        integer(i8) :: c0, c1, rate
        integer :: rep, inner, st, j
        character(len=msglen) :: m
        call dynamics_setup(model, ws)
        allocate (x(ws%nfree), xd(ws%nfree), xdd(ws%nfree))
        call rng%seed(7)
        do j = 1, ws%nfree
            r = rng%uniform(0.0_wp, 1.0_wp)
            x(j) = xbase(ws%ifree(j)) + 0.001_wp*(r - 0.5_wp)
            xd(j) = rng%uniform(-0.5_wp, 0.5_wp)
        end do
        call dynamics_evaluate(model, ws, 0.01_wp, x, xd, xdd, st, m)
        if (st /= 0) error stop 'bench_contact: the evaluation failed: '//trim(m)
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

end program bench_contact
