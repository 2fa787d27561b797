!> Output channels of a run: named scalar time histories computed from the
!! state of the last dynamics evaluation -- head kinematics, T1 motion,
!! occipital-condyle loads, joint rotations and element forces.
!!
!! Occipital-condyle (OC) loads are those the head exerts on the neck at the
!! head's joint point, in head axes, from the head's Newton-Euler balance:
!! tension (Fz) and flexion (My) positive.
module hn_channels
    use hn_kinds, only: wp, zero, g_std, deg
    use hn_case, only: case_t
    use hn_dynamics, only: dyn_workspace_t, energy_t
    use hn_kinematics, only: body_accelerations
    use hn_applied, only: applied_vector, applied_couple
    use hn_rotation, only: cross
    use hn_model, only: fam_discs, fam_ligaments, fam_muscles, fam_limits
    use hn_line_elements, only: muscle_hill
    implicit none
    private

    public :: channel_set_t, channels_define, channels_compute

    integer, parameter, public :: chname_len = 24

    !> Names, units, listing groups and current values of the channels.
    type :: channel_set_t
        integer :: n = 0
        character(len=chname_len), allocatable :: name(:)
        character(len=12), allocatable :: units(:)
        character(len=16), allocatable :: group(:)
        real(wp), allocatable :: value(:)
        real(wp) :: head_r0(3) = zero      !! head mass centre relative to T1's origin at the start [m]
        real(wp) :: t1_r0(3) = zero
        real(wp) :: e0 = zero              !! total energy at the start [J]
    end type channel_set_t

    character(len=2), parameter :: rot_names(3) = ['RX', 'RY', 'RZ']

contains

    subroutine add(ch, name, units, group)
        type(channel_set_t), intent(inout) :: ch
        character(len=*), intent(in) :: name, units, group
        character(len=chname_len) :: nm
        character(len=12) :: un
        character(len=16) :: gr
        nm = name; un = units; gr = group
        ch%name = [character(len=chname_len) :: ch%name, nm]
        ch%units = [character(len=12) :: ch%units, un]
        ch%group = [character(len=16) :: ch%group, gr]
        ch%n = ch%n + 1
    end subroutine add

    !> The channel list of a case.
    subroutine channels_define(cs, ch)
        type(case_t), intent(in) :: cs
        type(channel_set_t), intent(out) :: ch
        integer :: k, e, m
        allocate (ch%name(0), ch%units(0), ch%group(0))
        call add(ch, 'HEAD_AX', 'g', 'HEAD')
        call add(ch, 'HEAD_AZ', 'g', 'HEAD')
        call add(ch, 'HEAD_AR', 'g', 'HEAD')
        call add(ch, 'HEAD_ALPHY', 'rad/s^2', 'HEAD')
        call add(ch, 'HEAD_OMEGY', 'rad/s', 'HEAD')
        call add(ch, 'HEAD_THETY', 'deg', 'HEAD')
        call add(ch, 'HEAD_DX', 'mm', 'HEAD')       ! relative to T1's (translating) origin
        call add(ch, 'HEAD_DZ', 'mm', 'HEAD')
        call add(ch, 'HEAD_AY', 'g', 'HEAD 3D')
        call add(ch, 'HEAD_AXL', 'g', 'HEAD 3D')
        call add(ch, 'HEAD_AYL', 'g', 'HEAD 3D')
        call add(ch, 'HEAD_AZL', 'g', 'HEAD 3D')
        call add(ch, 'HEAD_ALPHX', 'rad/s^2', 'HEAD 3D')
        call add(ch, 'HEAD_ALPHZ', 'rad/s^2', 'HEAD 3D')
        call add(ch, 'HEAD_OMEGX', 'rad/s', 'HEAD 3D')
        call add(ch, 'HEAD_OMEGZ', 'rad/s', 'HEAD 3D')
        call add(ch, 'HEAD_DY', 'mm', 'HEAD 3D')
        call add(ch, 'T1_AX', 'g', 'T1')
        call add(ch, 'T1_AZ', 'g', 'T1')
        call add(ch, 'T1_THETY', 'deg', 'T1')
        call add(ch, 'T1_DX', 'mm', 'T1')
        call add(ch, 'OC_FX', 'N', 'OC LOADS')
        call add(ch, 'OC_FY', 'N', 'OC LOADS')
        call add(ch, 'OC_FZ', 'N', 'OC LOADS')
        call add(ch, 'OC_MX', 'N m', 'OC LOADS')
        call add(ch, 'OC_MY', 'N m', 'OC LOADS')
        call add(ch, 'OC_MZ', 'N m', 'OC LOADS')
        do m = 1, 3
            do k = 1, cs%model%tree%nbody
                if (cs%model%tree%parent(k) == 0) cycle
                call add(ch, trim(cs%model%tree%name(k))//'_'//rot_names(m), 'deg', 'JOINTS '//rot_names(m))
            end do
        end do
        do e = 1, size(cs%model%discs)
            call add(ch, trim(cs%model%discs(e)%name)//'_P', 'N', 'DISC AXIAL')
        end do
        do e = 1, size(cs%model%discs)
            call add(ch, trim(cs%model%discs(e)%name)//'_VX', 'N', 'DISC SHEAR X')
        end do
        do e = 1, size(cs%model%discs)
            call add(ch, trim(cs%model%discs(e)%name)//'_MY', 'N m', 'DISC MOMENT Y')
        end do
        do e = 1, size(cs%model%ligaments)
            call add(ch, trim(cs%model%ligaments(e)%name), 'N', 'LIGAMENTS')
        end do
        do e = 1, size(cs%model%muscles)
            call add(ch, trim(cs%model%muscles(e)%name), 'N', 'MUSCLES')
            if (cs%model%muscles(e)%law == muscle_hill) &
                call add(ch, 'A_'//trim(cs%model%muscles(e)%name), '-', 'MUSCLE ACTIVATION')
        end do
        do e = 1, size(cs%model%limits)
            k = cs%model%limits(e)%body
            m = cs%model%limits(e)%local
            call add(ch, 'L_'//trim(cs%model%tree%name(k))//'_'//trim(coord_label(m)), &
                     merge('N    ', 'N m  ', m <= 3), 'JOINT LIMITS')
        end do
        call add(ch, 'E_KINETIC', 'J', 'ENERGY')
        call add(ch, 'E_GRAVITY', 'J', 'ENERGY')
        call add(ch, 'E_ELASTIC', 'J', 'ENERGY')
        call add(ch, 'E_HOLD', 'J', 'ENERGY')
        call add(ch, 'E_DISSIP', 'J', 'ENERGY')
        call add(ch, 'E_MUSCLE', 'J', 'ENERGY')
        call add(ch, 'W_APPLIED', 'J', 'ENERGY')
        call add(ch, 'W_PRESCR', 'J', 'ENERGY')
        call add(ch, 'E_BALANCE', 'J', 'ENERGY')
        allocate (ch%value(ch%n))
        ch%value = zero
    end subroutine channels_define

    pure function coord_label(m) result(s)
        integer, intent(in) :: m
        character(len=2) :: s
        character(len=2), parameter :: names(6) = ['TX', 'TY', 'TZ', 'RX', 'RY', 'RZ']
        s = names(m)
    end function coord_label

    !> Channel values at time t from the workspace of the evaluation at t
    !! and the energy terms there.
    subroutine channels_compute(cs, ws, t, en, ch)
        type(case_t), intent(in) :: cs
        type(dyn_workspace_t), intent(in) :: ws
        real(wp), intent(in) :: t
        type(energy_t), intent(in) :: en
        type(channel_set_t), intent(inout) :: ch
        real(wp) :: acc(3, cs%model%tree%nbody), alpha(3, cs%model%tree%nbody)
        real(wp) :: s(3, 3), ah(3), fext(3), mext(3), f(3), mo(3), rgo(3), iw(3), v(3), rel(3)
        integer :: h, k, e, i, m, j
        h = cs%head
        call body_accelerations(cs%model%tree, ws%kin, ws%xdd, acc, alpha)
        s = ws%kin%s(:, :, h)
        ah = acc(:, h)
        i = 0
        call put(ah(1)/g_std); call put(ah(3)/g_std); call put(norm2(ah)/g_std)
        call put(alpha(2, h)); call put(ws%kin%omega(2, h))
        call put(atan2(s(1, 3), s(3, 3))/deg)
        rel = ws%kin%r(:, h) - ws%kin%r(:, cs%t1) - ch%head_r0       ! head relative to T1's translation
        call put(1000*rel(1)); call put(1000*rel(3))
        call put(ah(2)/g_std)
        v = matmul(transpose(s), ah)/g_std
        call put(v(1)); call put(v(2)); call put(v(3))
        call put(alpha(1, h)); call put(alpha(3, h))
        call put(ws%kin%omega(1, h)); call put(ws%kin%omega(3, h))
        call put(1000*rel(2))
        k = cs%t1
        call put(acc(1, k)/g_std); call put(acc(3, k)/g_std)
        call put(atan2(ws%kin%s(1, 3, k), ws%kin%s(3, 3, k))/deg)
        call put(1000*(ws%kin%r(1, k) - ch%t1_r0(1)))

        ! occipital condyle: neck load on the head from the head's balance
        fext = cs%model%tree%mass(h)*cs%model%gravity
        mext = zero
        rgo = ws%kin%joint(:, h) - ws%kin%r(:, h)       ! mass centre -> OC
        do e = 1, size(cs%model%applied)
            if (cs%model%applied(e)%body /= h) cycle
            v = applied_vector(cs%model%applied(e), ws%kin, t)
            if (cs%model%applied(e)%kind == applied_couple) then
                mext = mext + v
            else
                fext = fext + v
                mext = mext + cross(matmul(s, cs%model%applied(e)%point), v)
            end if
        end do
        f = cs%model%tree%mass(h)*ah - fext                ! neck on head
        iw = matmul(ws%kin%inertia_r(:, :, h), ws%kin%omega(:, h))
        ! moments about the mass centre: I alpha + w x I w = M_neck(OC) + rgo x f + mext
        mo = matmul(ws%kin%inertia_r(:, :, h), alpha(:, h)) + cross(ws%kin%omega(:, h), iw) - cross(rgo, f) - mext
        v = -matmul(transpose(s), f)                       ! head on neck, head axes
        call put(v(1)); call put(v(2)); call put(v(3))
        v = -matmul(transpose(s), mo)
        call put(v(1)); call put(v(2)); call put(v(3))

        do m = 4, 6
            do k = 1, cs%model%tree%nbody
                if (cs%model%tree%parent(k) == 0) cycle
                j = cs%model%tree%dof_index(m, k)
                if (j > 0) then
                    call put(ws%x(j)/deg)
                else
                    call put(cs%model%tree%q_ref(m, k)/deg)
                end if
            end do
        end do
        do e = 1, size(cs%model%discs)
            call put(merge(ws%eo%disc(3, e), zero, cs%model%family_on(fam_discs)))
        end do
        do e = 1, size(cs%model%discs)
            call put(merge(ws%eo%disc(1, e), zero, cs%model%family_on(fam_discs)))
        end do
        do e = 1, size(cs%model%discs)
            call put(merge(ws%eo%disc(5, e), zero, cs%model%family_on(fam_discs)))
        end do
        do e = 1, size(cs%model%ligaments)
            call put(merge(ws%eo%ligament(1, e), zero, cs%model%family_on(fam_ligaments)))
        end do
        do e = 1, size(cs%model%muscles)
            call put(merge(ws%eo%muscle(1, e), zero, cs%model%family_on(fam_muscles)))
            if (cs%model%muscles(e)%law == muscle_hill) &
                call put(merge(ws%eo%muscle(3, e), zero, cs%model%family_on(fam_muscles)))
        end do
        do e = 1, size(cs%model%limits)
            call put(merge(ws%eo%limit(e), zero, cs%model%family_on(fam_limits)))
        end do
        call put(en%kinetic); call put(en%gravity); call put(en%elastic); call put(en%hold)
        call put(en%dissipated); call put(en%muscle); call put(en%applied); call put(en%prescribed)
        call put(en%total - ch%e0)
    contains
        subroutine put(x)
            real(wp), intent(in) :: x
            i = i + 1
            ch%value(i) = x
        end subroutine put
    end subroutine channels_compute

end module hn_channels
