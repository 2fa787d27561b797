!> Scenes: merged bodies combine mass and inertia by the parallel-axis
!! theorem and move exactly like bodies locked together; the sagittal scene
!! assembles only its 27 coordinates and reproduces the symmetric full run.
program test_scene
    use hn_kinds, only: wp, zero, one, msglen
    use hn_tree, only: body_tree_t, tree_allocate, tree_build, dof_label
    use hn_scene, only: merge_bodies
    use hn_case, only: case_t
    use hn_deck, only: read_case
    use hn_dynamics, only: dyn_workspace_t, dynamics_setup, dynamics_evaluate
    use hn_run, only: run_state_t, run_result_t
    use hn_channels, only: channel_set_t, channels_define
    use hn_testing, only: test_suite_t
    use hn_test_models, only: rng_t, read_deck_lines
    implicit none

    type(test_suite_t) :: suite
    character(len=*), parameter :: scratch = 'test_scene_scratch.inp'
    character(len=80), allocatable :: base(:)
    integer :: k
    character(len=2), parameter :: coords(6) = ['TX', 'TY', 'TZ', 'RX', 'RY', 'RZ']

    base = [character(len=80) :: 'TITLE     SCENE TEST', 'CONTROL   0.1       1.0E-4    0.01      ADAMS', &
            'INCLUDE   input/head_neck_54dof.inp', 'HOLD      POSTURE']
    do k = 1, 6
        base = [character(len=80) :: base, 'PRESCRIB  T1        '//coords(k)//'        CONSTANT']
    end do

    call test_merge_parallel_axis()
    call test_merge_equals_locked()
    call test_sagittal_assembles_27()
    call test_sagittal_equals_full()
    call suite%finish()

contains

    !> Two bodies 0.1 m apart along z merged: mass sum, mass centre at the
    !! mass-weighted mean, inertia I1 + I2 + parallel-axis terms (by hand).
    subroutine test_merge_parallel_axis()
        type(body_tree_t) :: t
        integer :: new_index(3), stat
        real(wp) :: shift(3, 3), expect(3, 3)
        character(len=msglen) :: msg
        call tree_allocate(t, 3)
        t%mass = [5.0_wp, 1.0_wp, 3.0_wp]
        t%inertia(:, :, 2) = reshape([0.02_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.03_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.04_wp], [3, 3])
        t%inertia(:, :, 3) = reshape([0.01_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.01_wp, 0.0_wp, 0.0_wp, 0.0_wp, 0.02_wp], [3, 3])
        t%joint_parent(:, 3) = [0.0_wp, 0.0_wp, 0.06_wp]
        t%joint_child(:, 3) = [0.0_wp, 0.0_wp, -0.04_wp]       ! body 3's centre 0.1 m above body 2's
        call tree_build(t, stat, msg)
        call merge_bodies(t, 2, [3], new_index, shift, stat, msg)
        ! mass centre 3 * 0.1 / 4 = 0.075 above body 2's; distances 0.075 and 0.025
        expect = t%inertia(:, :, 2)*0 + reshape([0.03_wp + 1*0.075_wp**2 + 3*0.025_wp**2, 0.0_wp, 0.0_wp, &
                                                 0.0_wp, 0.04_wp + 1*0.075_wp**2 + 3*0.025_wp**2, 0.0_wp, &
                                                 0.0_wp, 0.0_wp, 0.06_wp], [3, 3])
        call suite%check(stat == 0 .and. t%nbody == 2 .and. abs(t%mass(2) - 4.0_wp) < 1.0e-15_wp .and. &
                         maxval(abs(t%inertia(:, :, 2) - expect)) < 1.0e-15_wp .and. &
                         abs(shift(3, 2) + 0.075_wp) < 1.0e-15_wp .and. abs(shift(3, 3) - 0.025_wp) < 1.0e-15_wp .and. &
                         all(new_index == [1, 2, 2]), 'MERGE: mass, mass centre and parallel-axis inertia by hand')
    end subroutine test_merge_parallel_axis

    !> C1 merged into C2 moves exactly like C1 with its six coordinates
    !! locked to C2: the same accelerations of every other coordinate.
    subroutine test_merge_equals_locked()
        type(case_t) :: a, b
        type(dyn_workspace_t) :: wa, wb
        type(rng_t) :: rng
        real(wp), allocatable :: xa(:), xda(:), xdda(:), xb(:), xdb(:), xddb(:)
        integer :: sa, sb, j, jb
        character(len=msglen) :: ma, mb
        real(wp) :: err, scale
        call read_deck_lines(scratch, [character(len=80) :: base, &
                             'LOCK      C1        TX        TY        TZ        RX        RY        RZ'], a, sa, ma)
        call read_deck_lines(scratch, [character(len=80) :: base, 'MERGE     C2        C1'], b, sb, mb)
        if (sa /= 0 .or. sb /= 0) then
            call suite%check(.false., 'merge versus lock decks read', trim(ma)//' '//trim(mb)); return
        end if
        call dynamics_setup(a%model, wa)
        call dynamics_setup(b%model, wb)
        allocate (xa(wa%nfree), xda(wa%nfree), xdda(wa%nfree), xb(wb%nfree), xdb(wb%nfree), xddb(wb%nfree))
        do j = 1, wa%nfree
            xa(j) = rng%uniform(-0.05_wp, 0.05_wp)
            xda(j) = rng%uniform(-1.0_wp, 1.0_wp)
        end do
        ! the same state in B's numbering, by coordinate label
        do j = 1, wb%nfree
            jb = label_index(a, wa, dof_label(b%model%tree, wb%ifree(j)))
            xb(j) = xa(jb); xdb(j) = xda(jb)
        end do
        call dynamics_evaluate(a%model, wa, 0.0_wp, xa, xda, xdda, sa, ma)
        call dynamics_evaluate(b%model, wb, 0.0_wp, xb, xdb, xddb, sb, mb)
        err = zero
        scale = maxval(abs(xdda))
        do j = 1, wb%nfree
            err = max(err, abs(xddb(j) - xdda(label_index(a, wa, dof_label(b%model%tree, wb%ifree(j))))))
        end do
        call suite%check(wa%nfree == 42 .and. wb%nfree == 42 .and. err < 1.0e-9_wp*scale, &
                         'C1 merged into C2 = C1 locked to C2: same accelerations of the other 42 coordinates', &
                         'largest difference '//real_text(err)//' of '//real_text(scale))
    end subroutine test_merge_equals_locked

    integer function label_index(cs, ws, label) result(j)
        type(case_t), intent(in) :: cs
        type(dyn_workspace_t), intent(in) :: ws
        character(len=*), intent(in) :: label
        do j = 1, ws%nfree
            if (dof_label(cs%model%tree, ws%ifree(j)) == label) return
        end do
        j = 1
    end function label_index

    !> The sagittal scene has 27 active coordinates and an a_ij of 27 x 27.
    subroutine test_sagittal_assembles_27()
        type(case_t) :: cs
        type(dyn_workspace_t) :: ws
        integer :: stat
        character(len=msglen) :: msg
        call read_deck_lines(scratch, [character(len=80) :: base, 'SCENE     SAGITTAL'], cs, stat, msg)
        if (stat /= 0) then
            call suite%check(.false., 'sagittal deck read', trim(msg)); return
        end if
        call dynamics_setup(cs%model, ws)
        call suite%check(cs%model%tree%ndof == 27 .and. all(shape(ws%a) == [27, 27]) .and. ws%nfree == 24 .and. &
                         size(ws%kin%w, 2) == 27 .and. maxval(cs%model%tree%chain_len) == 27, &
                         'sagittal scene: 27 coordinates, a_ij and the partial velocities sized 27, nothing for locked ones')
    end subroutine test_sagittal_assembles_27

    !> The NBDL sled is symmetric: the 54-DOF run keeps every out-of-plane
    !! quantity at zero and agrees with the 27-DOF sagittal run to the
    !! integration tolerance.
    subroutine test_sagittal_equals_full()
        type(case_t) :: full, sag
        type(run_result_t) :: rf, rs
        type(channel_set_t) :: ch
        integer :: stat, lu, i, j, n
        character(len=msglen) :: msg
        character(len=10), parameter :: inplane(6) = [character(len=10) :: 'HEAD_THETY', 'HEAD_OMEGY', 'HEAD_AX', &
                                                      'HEAD_AZ', 'OC_FZ', 'OC_MY']
        character(len=10), parameter :: outplane(6) = [character(len=10) :: 'HEAD_AY', 'HEAD_OMEGX', 'HEAD_OMEGZ', &
                                                       'OC_FY', 'OC_MX', 'OC_MZ']
        real(wp) :: dev, outmax, scale
        call read_case('input/nbdl15g.inp', 'input/nbdl15g.inp', full, stat, msg)
        call read_deck_lines(scratch, [character(len=80) :: 'INCLUDE   input/nbdl15g.inp', 'SCENE     SAGITTAL'], sag, stat, msg)
        if (stat /= 0) then
            call suite%check(.false., 'sagittal NBDL deck read', trim(msg)); return
        end if
        full%t_end = 0.15_wp; sag%t_end = 0.15_wp
        full%rtol = 1.0e-8_wp; sag%rtol = 1.0e-8_wp
        full%atol = 1.0e-11_wp; sag%atol = 1.0e-11_wp
        full%sample_dt = 1.0e-3_wp; sag%sample_dt = 1.0e-3_wp
        call channels_define(full, ch)
        open (newunit=lu, file='/dev/null', action='write')
        block
            type(run_state_t) :: run
            call run%execute(full, lu, '', rf, keep_samples=.true.)
        end block
        block
            type(run_state_t) :: run
            call run%execute(sag, lu, '', rs, keep_samples=.true.)
        end block
        close (lu)
        dev = zero; outmax = zero
        n = min(size(rf%samples_t), size(rs%samples_t))
        do i = 1, size(inplane)
            j = findloc(ch%name, inplane(i), dim=1)
            scale = maxval(abs(rf%samples(j, 1:n)))
            dev = max(dev, maxval(abs(rf%samples(j, 1:n) - rs%samples(j, 1:n)))/scale)
        end do
        do i = 1, size(outplane)
            j = findloc(ch%name, outplane(i), dim=1)
            outmax = max(outmax, maxval(abs(rf%samples(j, 1:n))))
        end do
        call suite%check(rf%exit_code == 0 .and. rs%exit_code == 0 .and. n == 151 .and. dev < 1.0e-5_wp .and. &
                         outmax < 1.0e-8_wp, 'NBDL sled: 54-DOF and 27-DOF sagittal runs agree, out-of-plane motion zero', &
                         'largest in-plane difference '//real_text(dev)//' of range; largest out-of-plane value '// &
                         real_text(outmax))
    end subroutine test_sagittal_equals_full

    function real_text(x) result(s)
        real(wp), intent(in) :: x
        character(len=10) :: s
        write (s, '(es10.3)') x
    end function real_text

end program test_scene
