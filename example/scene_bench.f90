!> Scene benchmark (not a test): the NBDL 15 g deck run as the full 54-DOF
!! model and as reduced scenes -- sagittal (27 DOF), C1 merged into C2, a
!! 3-body head/neck (C7 ... C1 merged), both, muscles off -- with the
!! deck's integrator and tolerance: wall time, evaluations, and how far the
!! head kinematics move from the full model's (largest difference over the
!! run, and the change of the peak). A scene the deck cannot build (a
!! MERGE of bodies with a neutral rotation between them, docs/deck-format.md)
!! is reported with the program's reason, and the benchmark goes on.
!!
!!   fpm run --example scene_bench --profile release
program scene_bench
    use hn_kinds, only: wp, msglen
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_run, only: run_state_t, run_result_t
    use hn_channels, only: channel_set_t, channels_define
    implicit none

    character(len=10), parameter :: chans(5) = [character(len=10) :: 'HEAD_THETY', 'HEAD_OMEGY', 'HEAD_ALPHY', &
                                                'HEAD_AX', 'HEAD_AZ']
    character(len=80), parameter :: merge3 = 'MERGE     C7        C6        C5        C4        C3        C2        C1'
    type(run_result_t) :: ref, res
    type(channel_set_t) :: ch
    integer :: idx(5), k
    character(len=msglen) :: msg

    call run_scene([character(len=80) :: ''], ref, idx, ch, msg)
    if (len_trim(msg) > 0) error stop trim(msg)
    write (*, '(a)') 'scene                         DOF  free   wall (s)    evals   max |d theta| (deg)  ' // &
        'd peak theta  max |d omega| (rad/s)  d peak alpha (rad/s2)  d peak ax (g)'
    call report('full 54-DOF model', [character(len=80) :: ''])
    call report('sagittal', [character(len=80) :: 'SCENE     SAGITTAL'])
    call report('C1 merged into C2', [character(len=80) :: 'MERGE     C2        C1'])
    call report('3-body head/neck', [character(len=80) :: merge3])
    call report('3-body, sagittal', [character(len=80) :: merge3, 'SCENE     SAGITTAL'])
    call report('muscles off', [character(len=80) :: 'FAMILY    MUSCLES   OFF'])
    call report('sagittal, muscles off', [character(len=80) :: 'SCENE     SAGITTAL', 'FAMILY    MUSCLES   OFF'])

contains

    subroutine run_scene(extra, r, ix, c, msg)
        character(len=*), intent(in) :: extra(:)
        type(run_result_t), intent(out) :: r
        integer, intent(out) :: ix(5)
        type(channel_set_t), intent(out) :: c
        character(len=msglen), intent(out) :: msg   !! why the deck was refused ('' when it ran)
        type(case_t) :: cs
        character(len=*), parameter :: fname = 'scene_bench_deck.inp'
        integer :: u, stat, i
        open (newunit=u, file=fname, status='replace', action='write')
        write (u, '(a)') 'INCLUDE   input/nbdl15g.inp'
        do i = 1, size(extra)
            if (len_trim(extra(i)) > 0) write (u, '(a)') trim(extra(i))
        end do
        close (u)
        call read_case(fname, fname, cs, stat, msg)
        open (newunit=u, file=fname, status='old')
        close (u, status='delete')
        if (stat /= 0) return
        msg = ''
        call channels_define(cs, c)
        do i = 1, 5
            ix(i) = findloc(c%name, chans(i), dim=1)
        end do
        open (newunit=u, file='/dev/null', action='write')
        block
            type(run_state_t) :: run
            call run%execute(cs, u, '', r, keep_samples=.true.)
        end block
        close (u)
        r%nsteps = cs%model%tree%ndof
        r%njac = count(.not. cs%model%prescribed)
    end subroutine run_scene

    subroutine report(label, extra)
        character(len=*), intent(in) :: label
        character(len=*), intent(in) :: extra(:)
        integer :: ix(5)
        real(wp) :: dth, dom, dpk_th, dpk_al, dpk_ax
        character(len=msglen) :: why
        call run_scene(extra, res, ix, ch, why)
        if (len_trim(why) > 0) then
            write (*, '(a28,a)') label, '  refused: '//trim(why)
            return
        end if
        dth = maxval(abs(res%samples(ix(1), :) - ref%samples(idx_ref(1), :)))
        dom = maxval(abs(res%samples(ix(2), :) - ref%samples(idx_ref(2), :)))
        dpk_th = maxval(res%samples(ix(1), :)) - maxval(ref%samples(idx_ref(1), :))
        dpk_al = maxval(res%samples(ix(3), :)) - maxval(ref%samples(idx_ref(3), :))
        dpk_ax = minval(res%samples(ix(4), :)) - minval(ref%samples(idx_ref(4), :))
        write (*, '(a28,i5,i6,f11.3,i9,es21.3,f14.2,es23.3,f23.1,f15.2)') label, res%nsteps, res%njac, res%wall, &
            res%nevals, dth, dpk_th, dom, dpk_al, dpk_ax
    end subroutine report

    integer function idx_ref(i)
        integer, intent(in) :: i
        idx_ref = idx(i)
    end function idx_ref

end program scene_bench
