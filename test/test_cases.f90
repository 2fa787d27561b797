!> Every case deck in input/ end to end: read, run, listing and HDF5 file
!! written, then physical sanity from the file's channels: the head flexes
!! forward in the sled, the forehead impacts decelerate the head, nothing
!! is NaN.
program test_cases
    use hn_kinds, only: wp, msglen
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_run, only: run_state_t, run_result_t
    use hn_h5, only: h5_read_real, h5_dims, h5_read_string_attr
    use hn_testing, only: test_suite_t
    implicit none

    type(test_suite_t) :: suite

    call test_nbdl_sled()
    call test_pendulum_case('6-1')
    call test_pendulum_case('6-2')
    call test_pendulum_case('6-5')
    call test_hybrid3_flexion()
    call suite%finish()

contains

    !> Run input/<name>.inp with results in test_<name>.h5; ok if it ran complete.
    subroutine run_deck(name, ok, h5name)
        character(len=*), intent(in) :: name
        logical, intent(out) :: ok
        character(len=:), allocatable, intent(out) :: h5name
        type(case_t) :: cs
        type(run_result_t) :: res
        integer :: lu, stat
        character(len=msglen) :: msg
        character(len=16) :: status
        h5name = 'test_'//name//'.h5'
        call read_case('input/'//name//'.inp', 'input/'//name//'.inp', cs, stat, msg)
        ok = stat == 0
        if (.not. ok) then
            print '(a)', 'deck error: '//trim(msg)
            return
        end if
        open (newunit=lu, status='scratch')
        block
            type(run_state_t) :: run
            call run%execute(cs, lu, h5name, res)
        end block
        close (lu)
        call h5_read_string_attr(h5name, '/', 'status', status, stat)
        ok = res%exit_code == 0 .and. stat == 0 .and. status == 'complete'
        if (.not. ok) print '(a)', 'run: '//trim(res%message)
    end subroutine run_deck

    !> A channel of the result file.
    subroutine channel(h5name, cname, v)
        character(len=*), intent(in) :: h5name, cname
        real(wp), allocatable, intent(out) :: v(:)
        integer, allocatable :: d(:)
        integer :: stat
        call h5_dims(h5name, '/channels/'//cname, d, stat)
        allocate (v(d(1)))
        call h5_read_real(h5name, '/channels/'//cname, v, stat)
    end subroutine channel

    !> True when every channel of the file is finite.
    logical function all_finite(h5name) result(ok)
        character(len=*), intent(in) :: h5name
        character(len=*), parameter :: names(8) = [character(len=10) :: 'HEAD_AX', 'HEAD_AZ', 'HEAD_ALPHY', &
                                                   'HEAD_OMEGY', 'HEAD_THETY', 'OC_FX', 'OC_FZ', 'OC_MY']
        real(wp), allocatable :: v(:)
        integer :: k
        ok = .true.
        do k = 1, size(names)
            call channel(h5name, trim(names(k)), v)
            ok = ok .and. all(abs(v) <= huge(v))
        end do
    end function all_finite

    subroutine cleanup(h5name)
        character(len=*), intent(in) :: h5name
        integer :: u
        open (newunit=u, file=h5name, status='old')
        close (u, status='delete')
    end subroutine cleanup

    subroutine test_nbdl_sled()
        character(len=:), allocatable :: f
        real(wp), allocatable :: th(:), t(:), ax(:)
        integer, allocatable :: d(:)
        integer :: stat, imax
        logical :: ok
        character(len=120) :: det
        call run_deck('nbdl15g', ok, f)
        if (.not. ok) then
            call suite%check(.false., 'nbdl15g.inp runs to the end'); return
        end if
        call channel(f, 'HEAD_THETY', th)
        call channel(f, 'HEAD_AX', ax)
        call h5_dims(f, '/time', d, stat)
        allocate (t(d(1)))
        call h5_read_real(f, '/time', t, stat)
        imax = maxloc(th, dim=1)
        write (det, '(a,f7.2,a,f7.1,a,f7.2,a)') 'peak flexion ', th(imax), ' deg at ', 1000*t(imax), &
            ' ms, head x-acc min ', minval(ax), ' g'
        call suite%check(all_finite(f) .and. th(imax) > 30.0_wp .and. t(imax) > 0.1_wp .and. minval(ax) < -10.0_wp, &
                         'NBDL 15 g sled: head flexes forward after the pulse, decelerates, no NaN', det)
        call cleanup(f)
    end subroutine test_nbdl_sled

    subroutine test_pendulum_case(id)
        character(len=*), intent(in) :: id
        character(len=:), allocatable :: f
        real(wp), allocatable :: ax(:), dx(:), t(:)
        integer, allocatable :: d(:)
        integer :: stat, imin
        logical :: ok
        character(len=120) :: det
        call run_deck('case'//id, ok, f)
        if (.not. ok) then
            call suite%check(.false., 'case'//id//'.inp runs to the end'); return
        end if
        call channel(f, 'HEAD_AX', ax)
        call channel(f, 'HEAD_DX', dx)
        call h5_dims(f, '/time', d, stat)
        allocate (t(d(1)))
        call h5_read_real(f, '/time', t, stat)
        imin = minloc(ax, dim=1)
        write (det, '(a,f8.2,a,f6.1,a,f8.2,a)') 'head x-acc min ', ax(imin), ' g at ', 1000*t(imin), &
            ' ms; head x-displacement at 40 ms ', dx(401), ' mm'
        call suite%check(all_finite(f) .and. ax(imin) < -20.0_wp .and. t(imin) > 0.005_wp .and. &
                         t(imin) < 0.025_wp .and. dx(401) < -5.0_wp, &
                         'case '//id//': the forehead impact decelerates the head during the pulse, no NaN', det)
        call cleanup(f)
    end subroutine test_pendulum_case

    subroutine test_hybrid3_flexion()
        character(len=:), allocatable :: f
        real(wp), allocatable :: th(:), my(:)
        logical :: ok
        character(len=120) :: det
        call run_deck('hybrid3_flexion', ok, f)
        if (.not. ok) then
            call suite%check(.false., 'hybrid3_flexion.inp runs to the end'); return
        end if
        call channel(f, 'HEAD_THETY', th)
        call channel(f, 'OC_MY', my)
        write (det, '(a,f7.2,a,f8.2,a)') 'peak flexion ', maxval(th), ' deg, peak OC flexion moment ', maxval(my), ' N m'
        call suite%check(all_finite(f) .and. maxval(th) > 20.0_wp .and. maxval(my) > 10.0_wp, &
                         'Hybrid III pendulum input: the head flexes and loads the neck in flexion, no NaN', det)
        call cleanup(f)
    end subroutine test_hybrid3_flexion

end program test_cases
