!> Injury assessment of a run from its sampled channels, filtered as the
!! regulations prescribe: HIC15 and HIC36 of the head resultant acceleration
!! (CFC 1000), Nij in its four modes at the occipital condyle (CFC 600), NIC
!! (CFC 60), and the peak upper-neck tension, compression, shear and moments
!! (CFC 600). Reference values (of the chosen occupant's dummy, not limits
!! of this human model) from hn_injury's `occupants`. NIC from the
!! x-accelerations in inertial axes (default) or along the head's x axis.
!! The rear-impact and lateral criteria of hn_whiplash where the run has
!! what they need: the NDC points, the peak lateral upper-neck moment and
!! shear and the head's lateral bending relative to T1, the peak T1 and
!! head x-accelerations; and the run's loading direction (scene_direction),
!! which decides which criteria the listing shows.
module hn_assessment
    use hn_kinds, only: wp, zero, g_std
    use hn_filters, only: cfc_filter
    use hn_injury, only: hic, nij, nic, nij_intercepts_t, occupants, occupant_index
    use hn_whiplash, only: ndc_points_t, ndc_points, scene_direction
    implicit none
    private

    public :: assessment_t, assess, criteria_input_t, criteria_input_allocate, criteria_input_from
    public :: criteria_channels, ncriteria_columns

    !> The channels of a run the assessment reads, by name: the first columns
    !! of criteria_input_from, in this order (the only list of them).
    character(len=8), parameter :: criteria_channels(13) = [character(len=8) :: 'HEAD_AX', 'HEAD_AY', 'HEAD_AZ', &
                                                            'T1_AX', 'OC_FX', 'OC_FZ', 'OC_MY', 'OC_FY', 'OC_MX', &
                                                            'HT1_RX', 'HT1_RY', 'HT1_DX', 'HT1_DZ']
    !> Columns of criteria_input_from: the criteria_channels, then the head's
    !! and T1's x-accelerations along the head's x axis.
    integer, parameter :: ncriteria_columns = size(criteria_channels) + 2

    !> The sampled channels the assessment reads, by name.
    type :: criteria_input_t
        real(wp), allocatable :: head_ax(:)   !! head mass-centre x-acceleration, global axes [g] (channel HEAD_AX)
        real(wp), allocatable :: head_ay(:)   !! ... y [g] (HEAD_AY)
        real(wp), allocatable :: head_az(:)   !! ... z [g] (HEAD_AZ)
        real(wp), allocatable :: t1_ax(:)     !! T1 x-acceleration [g] (T1_AX)
        real(wp), allocatable :: oc_fx(:)     !! occipital-condyle shear force [N] (OC_FX)
        real(wp), allocatable :: oc_fz(:)     !! occipital-condyle axial force, tension positive [N] (OC_FZ)
        real(wp), allocatable :: oc_my(:)     !! occipital-condyle moment, flexion positive [N m] (OC_MY)
        real(wp), allocatable :: oc_fy(:)     !! occipital-condyle lateral shear force [N] (OC_FY)
        real(wp), allocatable :: oc_mx(:)     !! occipital-condyle lateral bending moment [N m] (OC_MX)
        real(wp), allocatable :: ht1_rx(:)    !! head lateral bending relative to T1 [deg] (HT1_RX)
        real(wp), allocatable :: ht1_ry(:)    !! head flexion relative to T1, flexion positive [deg] (HT1_RY)
        real(wp), allocatable :: ht1_dx(:)    !! head x relative to T1 in T1's axes, from the start [mm] (HT1_DX)
        real(wp), allocatable :: ht1_dz(:)    !! head z relative to T1 in T1's axes, from the start [mm] (HT1_DZ)
        real(wp), allocatable :: head_axh(:)  !! head mass-centre acceleration along the head's x axis [g] (HEAD_AXL)
        real(wp), allocatable :: t1_axh(:)    !! T1 mass-centre acceleration along the head's x axis [g]
    end type criteria_input_t

    !> Criteria values, where they occur, and their time histories.
    type :: assessment_t
        logical :: computed = .false.
        character(len=120) :: note = ''
        real(wp) :: hic15 = zero, hic15_t1 = zero, hic15_t2 = zero
        real(wp) :: hic36 = zero, hic36_t1 = zero, hic36_t2 = zero
        real(wp) :: nij_max(4) = zero, nij_time(4) = zero          !! NTE, NTF, NCE, NCF
        real(wp) :: nic_max = zero, nic_time = zero
        real(wp) :: tension = zero, tension_t = zero, compression = zero, compression_t = zero
        real(wp) :: shear = zero, shear_t = zero, flexion = zero, flexion_t = zero
        real(wp) :: extension = zero, extension_t = zero
        character(len=8) :: direction = 'FRONTAL'                  !! FRONTAL, REAR or LATERAL (hn_whiplash's scene_direction)
        real(wp) :: lat_moment = zero, lat_moment_t = zero         !! largest |OC_MX|, CFC 600 [N m]
        real(wp) :: lat_shear = zero, lat_shear_t = zero           !! largest |OC_FY|, CFC 600 [N]
        real(wp) :: lat_bend = zero, lat_bend_t = zero             !! HT1_RX of largest magnitude [deg], signed
        real(wp) :: t1_ax_max = zero, t1_ax_max_t = zero           !! highest T1 x-acceleration, CFC 60 [g] (NIC's frame)
        real(wp) :: head_ax_max = zero, head_ax_max_t = zero       !! highest head x-acceleration, CFC 60 [g] (NIC's frame)
        type(ndc_points_t) :: ndc                                  !! NDC points (head relative to T1)
        real(wp), allocatable :: head_ar(:)                        !! CFC 1000 resultant [g]
        real(wp), allocatable :: nij_t(:, :)                       !! (nt, 4) Nij modes
        real(wp), allocatable :: nic_t(:)                          !! NIC [m^2/s^2]
        real(wp), allocatable :: fx(:), fz(:), my(:)               !! CFC 600 OC loads
        real(wp), allocatable :: fy(:), mx(:)                      !! CFC 600 OC lateral loads
        real(wp), allocatable :: nic_head(:), nic_t1(:)            !! CFC 60 x-accelerations NIC is computed from [m/s^2]
        integer :: occupant = 1                                    !! index in hn_injury's occupants (Nij, neck loads)
        character(len=8) :: nic_frame = 'INERTIAL'                 !! INERTIAL (global x) or HEAD (head x axis)
    end type assessment_t

contains

    !> Room for n samples of every input column, zero.
    pure subroutine criteria_input_allocate(hist, n)
        type(criteria_input_t), intent(out) :: hist   !! the columns
        integer, intent(in) :: n                      !! number of samples
        allocate (hist%head_ax(n), hist%head_ay(n), hist%head_az(n), hist%t1_ax(n), hist%oc_fx(n), &
                  hist%oc_fz(n), hist%oc_my(n), hist%oc_fy(n), hist%oc_mx(n), hist%ht1_rx(n), hist%ht1_ry(n), &
                  hist%ht1_dx(n), hist%ht1_dz(n), hist%head_axh(n), hist%t1_axh(n))
        hist%head_ax = zero; hist%head_ay = zero; hist%head_az = zero; hist%t1_ax = zero
        hist%oc_fx = zero; hist%oc_fz = zero; hist%oc_my = zero; hist%head_axh = zero; hist%t1_axh = zero
        hist%oc_fy = zero; hist%oc_mx = zero; hist%ht1_rx = zero; hist%ht1_ry = zero; hist%ht1_dx = zero
        hist%ht1_dz = zero
    end subroutine criteria_input_allocate

    !> The input columns from one array of samples: cols(:, k) is the k-th of
    !! the criteria_channels, then the head's and T1's x-accelerations along the
    !! head's x axis (ncriteria_columns columns).
    pure function criteria_input_from(cols) result(hist)
        real(wp), intent(in) :: cols(:, :)   !! (samples, ncriteria_columns), units as criteria_input_t
        type(criteria_input_t) :: hist
        hist%head_ax = cols(:, 1); hist%head_ay = cols(:, 2); hist%head_az = cols(:, 3)
        hist%t1_ax = cols(:, 4); hist%oc_fx = cols(:, 5); hist%oc_fz = cols(:, 6); hist%oc_my = cols(:, 7)
        hist%oc_fy = cols(:, 8); hist%oc_mx = cols(:, 9); hist%ht1_rx = cols(:, 10); hist%ht1_ry = cols(:, 11)
        hist%ht1_dx = cols(:, 12); hist%ht1_dz = cols(:, 13)
        hist%head_axh = cols(:, 14); hist%t1_axh = cols(:, 15)
    end function criteria_input_from

    !> Assess from the first n samples of hist, every dt [s] from t0.
    subroutine assess(t0, dt, hist, n, a, occupant, nic_frame)
        real(wp), intent(in) :: t0                    !! time of the first sample [s]
        real(wp), intent(in) :: dt                    !! sampling interval [s]
        type(criteria_input_t), intent(in) :: hist    !! the sampled input channels
        integer, intent(in) :: n                      !! number of samples taken
        type(assessment_t), intent(out) :: a          !! criteria (a%computed false with a%note when impossible)
        character(len=*), intent(in), optional :: occupant    !! code in hn_injury's occupants (default H50M)
        character(len=*), intent(in), optional :: nic_frame   !! NIC's x axis: INERTIAL (default) or HEAD
        real(wp), allocatable :: ax(:), ay(:), az(:)
        type(nij_intercepts_t) :: crit
        integer :: m, k
        if (present(occupant)) then
            a%occupant = occupant_index(occupant)
            if (a%occupant == 0) then
                a%occupant = 1
                a%note = 'not computed: unknown occupant "'//trim(occupant)//'"'
                return
            end if
        end if
        if (present(nic_frame)) then
            if (nic_frame /= 'INERTIAL' .and. nic_frame /= 'HEAD') then
                a%note = 'not computed: unknown NIC frame "'//trim(nic_frame)//'"'
                return
            end if
            a%nic_frame = nic_frame
        end if
        crit = occupants(a%occupant)%crit
        if (n < 3) then
            a%note = 'not computed: fewer than 3 samples'
            return
        end if
        if (dt > 1.0e-4_wp*(1 + 1.0e-9_wp)) then
            a%note = 'not computed: the HDF5 sampling is coarser than 0.1 ms (10 kHz), needed for CFC 1000 and 600'
            return
        end if
        a%computed = .true.
        allocate (ax(n), ay(n), az(n), a%head_ar(n), a%nij_t(n, 4), a%nic_t(n), a%fx(n), a%fz(n), a%my(n), &
                  a%nic_head(n), a%nic_t1(n), a%fy(n), a%mx(n))
        call cfc_filter(hist%head_ax(1:n), dt, 1000.0_wp, ax)
        call cfc_filter(hist%head_ay(1:n), dt, 1000.0_wp, ay)
        call cfc_filter(hist%head_az(1:n), dt, 1000.0_wp, az)
        a%head_ar = sqrt(ax**2 + ay**2 + az**2)
        call hic(a%head_ar, dt, 0.015_wp, a%hic15, a%hic15_t1, a%hic15_t2)
        call hic(a%head_ar, dt, 0.036_wp, a%hic36, a%hic36_t1, a%hic36_t2)
        a%hic15_t1 = a%hic15_t1 + t0; a%hic15_t2 = a%hic15_t2 + t0
        a%hic36_t1 = a%hic36_t1 + t0; a%hic36_t2 = a%hic36_t2 + t0

        call cfc_filter(hist%oc_fx(1:n), dt, 600.0_wp, a%fx)
        call cfc_filter(hist%oc_fz(1:n), dt, 600.0_wp, a%fz)
        call cfc_filter(hist%oc_my(1:n), dt, 600.0_wp, a%my)
        call nij(a%fz, a%my, crit, a%nij_t(:, 1), a%nij_t(:, 2), a%nij_t(:, 3), a%nij_t(:, 4))
        do k = 1, 4
            m = maxloc(a%nij_t(:, k), dim=1)
            a%nij_max(k) = a%nij_t(m, k)
            a%nij_time(k) = t0 + (m - 1)*dt
        end do
        call peak(a%fz, .true., a%tension, a%tension_t)
        call peak(a%fz, .false., a%compression, a%compression_t)
        call peak(abs(a%fx), .true., a%shear, a%shear_t)
        call peak(a%my, .true., a%flexion, a%flexion_t)
        call peak(a%my, .false., a%extension, a%extension_t)

        if (a%nic_frame == 'HEAD') then
            call cfc_filter(hist%head_axh(1:n)*g_std, dt, 60.0_wp, a%nic_head)
            call cfc_filter(hist%t1_axh(1:n)*g_std, dt, 60.0_wp, a%nic_t1)
        else
            call cfc_filter(hist%head_ax(1:n)*g_std, dt, 60.0_wp, a%nic_head)
            call cfc_filter(hist%t1_ax(1:n)*g_std, dt, 60.0_wp, a%nic_t1)
        end if
        call nic(a%nic_t1, a%nic_head, dt, a%nic_t)
        m = maxloc(a%nic_t, dim=1)
        a%nic_max = a%nic_t(m)
        a%nic_time = t0 + (m - 1)*dt
        call peak(a%nic_t1/g_std, .true., a%t1_ax_max, a%t1_ax_max_t)
        call peak(a%nic_head/g_std, .true., a%head_ax_max, a%head_ax_max_t)

        call cfc_filter(hist%oc_fy(1:n), dt, 600.0_wp, a%fy)
        call cfc_filter(hist%oc_mx(1:n), dt, 600.0_wp, a%mx)
        call peak(abs(a%mx), .true., a%lat_moment, a%lat_moment_t)
        call peak(abs(a%fy), .true., a%lat_shear, a%lat_shear_t)
        m = maxloc(abs(hist%ht1_rx(1:n)), dim=1)
        a%lat_bend = hist%ht1_rx(m)
        a%lat_bend_t = t0 + (m - 1)*dt
        a%ndc = ndc_points(hist%ht1_ry(1:n), hist%ht1_dx(1:n), hist%ht1_dz(1:n), t0, dt)
        a%direction = scene_direction(hist%ht1_rx(1:n), hist%ht1_ry(1:n))
    contains
        subroutine peak(x, highest, v, t)
            real(wp), intent(in) :: x(:)
            logical, intent(in) :: highest
            real(wp), intent(out) :: v, t
            integer :: i
            if (highest) then
                i = maxloc(x, dim=1)
            else
                i = minloc(x, dim=1)
            end if
            v = x(i)
            t = t0 + (i - 1)*dt
        end subroutine peak
    end subroutine assess

end module hn_assessment
