!> Rear-impact (whiplash) and lateral neck criteria from sampled histories,
!! and the rule that picks a run's loading direction:
!!  Nkm (Schmitt et al. 2002): Fx/Fint + My/Mint at the occipital condyle in
!!      four modes (flexion or extension, anterior or posterior shear);
!!  LNL (lower neck load index, Heitplatz et al. 2003): resultant lower-neck
!!      bending moment, shear force and axial force, each over its intercept;
!!  NDC (neck displacement criterion, Muser et al. 2000): the head's motion
!!      relative to T1 in the sagittal plane, as the points (angle, x) where
!!      extension and retraction peak;
!!  IV-NIC (Panjabi et al. 1999): each joint's rotation over its
!!      physiological range of motion in the same direction;
!!  head-restraint contact time: when the head first touches the
!!      restraint, from the contact's penetration channel.
!! The intercepts are arguments: none of them is set here (the sources were
!! not available to check them; docs/output-format.md lists them).
module hn_whiplash
    use hn_kinds, only: wp, zero
    use hn_injury, only: mode_sums
    implicit none
    private

    public :: nkm_intercepts_t, nkm, lnl_intercepts_t, lnl, ndc_points_t, ndc_points, iv_nic, scene_direction, &
              contact_onset

    !> Intercepts of Nkm [N, N m], all positive.
    type :: nkm_intercepts_t
        real(wp) :: fx_anterior = zero     !! shear intercept, anterior (Fx > 0) [N]
        real(wp) :: fx_posterior = zero    !! shear intercept, posterior (Fx < 0) [N]
        real(wp) :: my_flexion = zero      !! moment intercept, flexion (My > 0) [N m]
        real(wp) :: my_extension = zero    !! moment intercept, extension (My < 0) [N m]
    end type nkm_intercepts_t

    !> Intercepts of the LNL index [N m, N, N], all positive.
    type :: lnl_intercepts_t
        real(wp) :: moment = zero     !! resultant bending moment sqrt(Mx^2 + My^2) [N m]
        real(wp) :: shear = zero      !! resultant shear force sqrt(Fx^2 + Fy^2) [N]
        real(wp) :: axial = zero      !! axial force |Fz| [N]
    end type lnl_intercepts_t

    !> The NDC points of a run: where the head's extension and retraction
    !! relative to T1 peak, and the values of the other coordinates there.
    type :: ndc_points_t
        real(wp) :: ext_angle = zero, ext_dx = zero, ext_dz = zero, ext_time = zero   !! at the lowest angle (extension)
        real(wp) :: ret_dx = zero, ret_angle = zero, ret_dz = zero, ret_time = zero   !! at the lowest x (retraction)
        real(wp) :: flex_angle = zero, flex_dx = zero, flex_time = zero               !! at the highest angle (flexion)
    end type ndc_points_t

contains

    !> The four Nkm modes at every sample, zero where a mode does not apply:
    !! fx > 0 anterior, my > 0 flexion (the signs of OC_FX and OC_MY); fx = 0
    !! counts as anterior.
    pure subroutine nkm(fx, my, crit, nfa, nfp, nea, nep)
        real(wp), intent(in) :: fx(:)                       !! shear force at the OC, anterior positive [N]
        real(wp), intent(in) :: my(:)                       !! moment at the OC, flexion positive [N m]
        type(nkm_intercepts_t), intent(in) :: crit          !! intercepts (positive)
        real(wp), intent(out), dimension(size(fx)) :: nfa   !! flexion, anterior shear
        real(wp), intent(out), dimension(size(fx)) :: nfp   !! flexion, posterior shear
        real(wp), intent(out), dimension(size(fx)) :: nea   !! extension, anterior shear
        real(wp), intent(out), dimension(size(fx)) :: nep   !! extension, posterior shear
        call mode_sums(fx, my, crit%fx_anterior, crit%fx_posterior, crit%my_flexion, crit%my_extension, &
                       nfa, nea, nfp, nep)
    end subroutine nkm

    !> LNL(t) = sqrt(Mx^2 + My^2)/C_moment + sqrt(Fx^2 + Fy^2)/C_shear
    !! + |Fz|/C_axial from the lower-neck loads.
    pure subroutine lnl(fx, fy, fz, mx, my, crit, value)
        real(wp), intent(in) :: fx(:)                   !! lower-neck shear force x [N]
        real(wp), intent(in) :: fy(:)                   !! lower-neck shear force y [N]
        real(wp), intent(in) :: fz(:)                   !! lower-neck axial force [N]
        real(wp), intent(in) :: mx(:)                   !! lower-neck moment about x [N m]
        real(wp), intent(in) :: my(:)                   !! lower-neck moment about y [N m]
        type(lnl_intercepts_t), intent(in) :: crit      !! intercepts (positive)
        real(wp), intent(out) :: value(size(fx))        !! LNL at every sample
        value = sqrt(mx**2 + my**2)/crit%moment + sqrt(fx**2 + fy**2)/crit%shear + abs(fz)/crit%axial
    end subroutine lnl

    !> The NDC points from the head's sagittal rotation relative to T1
    !! (flexion positive) and its mass centre's x and z relative to T1
    !! (x < 0 retraction), sampled every dt from t0.
    pure function ndc_points(angle, dx, dz, t0, dt) result(p)
        real(wp), intent(in) :: angle(:)   !! head rotation relative to T1 about y, flexion positive [deg]
        real(wp), intent(in) :: dx(:)      !! head x relative to T1, from its start value [mm]
        real(wp), intent(in) :: dz(:)      !! head z relative to T1, from its start value [mm]
        real(wp), intent(in) :: t0         !! time of the first sample [s]
        real(wp), intent(in) :: dt         !! sampling interval [s]
        type(ndc_points_t) :: p
        integer :: i
        i = minloc(angle, dim=1)
        p%ext_angle = angle(i); p%ext_dx = dx(i); p%ext_dz = dz(i); p%ext_time = t0 + (i - 1)*dt
        i = minloc(dx, dim=1)
        p%ret_dx = dx(i); p%ret_angle = angle(i); p%ret_dz = dz(i); p%ret_time = t0 + (i - 1)*dt
        i = maxloc(angle, dim=1)
        p%flex_angle = angle(i); p%flex_dx = dx(i); p%flex_time = t0 + (i - 1)*dt
    end function ndc_points

    !> IV-NIC of each joint: the largest over the samples of its rotation
    !! divided by its physiological range in the rotation's direction
    !! (extension: rot < 0 over rom_extension; flexion: over rom_flexion).
    pure subroutine iv_nic(rot, rom_extension, rom_flexion, value, at)
        real(wp), intent(in) :: rot(:, :)            !! (samples, joints) joint rotations, flexion positive [deg]
        real(wp), intent(in) :: rom_extension(:)     !! each joint's extension range, positive [deg]
        real(wp), intent(in) :: rom_flexion(:)       !! each joint's flexion range, positive [deg]
        real(wp), intent(out) :: value(size(rot, 2)) !! peak IV-NIC of each joint
        integer, intent(out) :: at(size(rot, 2))     !! sample of each peak
        real(wp) :: r(size(rot, 1))
        integer :: j
        do j = 1, size(rot, 2)
            r = max(-rot(:, j), zero)/rom_extension(j) + max(rot(:, j), zero)/rom_flexion(j)
            at(j) = maxloc(r, dim=1)
            value(j) = r(at(j))
        end do
    end subroutine iv_nic

    !> The loading direction of a run from the head's rotation relative to
    !! T1: LATERAL when the largest lateral bending exceeds the largest
    !! flexion-extension, else REAR when the largest sagittal rotation is an
    !! extension and FRONTAL when it is a flexion.
    pure function scene_direction(lateral, sagittal) result(d)
        real(wp), intent(in) :: lateral(:)    !! lateral bending relative to T1 (HT1_RX) [deg]
        real(wp), intent(in) :: sagittal(:)   !! flexion-extension relative to T1 (HT1_RY), flexion positive [deg]
        character(len=8) :: d
        if (maxval(abs(lateral)) > maxval(abs(sagittal))) then
            d = 'LATERAL'
        else if (-minval(sagittal) > maxval(sagittal)) then
            d = 'REAR'
        else
            d = 'FRONTAL'
        end if
    end function scene_direction

    !> The time of first contact from a contact's sampled penetration d
    !! (negative: the gap): where d first rises from <= 0 to > 0, the zero
    !! crossing interpolated linearly between the two samples; t0 when the
    !! first sample is already in contact; found false (and -1) when d
    !! never becomes positive.
    pure subroutine contact_onset(depth, t0, dt, t, found)
        real(wp), intent(in) :: depth(:)   !! penetration at every sample, > 0 in contact [any length unit]
        real(wp), intent(in) :: t0         !! time of the first sample [s]
        real(wp), intent(in) :: dt         !! sampling interval [s]
        real(wp), intent(out) :: t         !! time of first contact [s] (-1 without contact)
        logical, intent(out) :: found      !! the penetration became positive
        integer :: i
        t = -1.0_wp
        found = .false.
        if (size(depth) == 0) return
        if (depth(1) > zero) then
            t = t0
            found = .true.
            return
        end if
        do i = 2, size(depth)
            if (depth(i) > zero) then
                t = t0 + (i - 2 + depth(i - 1)/(depth(i - 1) - depth(i)))*dt
                found = .true.
                return
            end if
        end do
    end subroutine contact_onset

end module hn_whiplash
