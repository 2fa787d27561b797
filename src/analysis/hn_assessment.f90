!> Injury assessment of a run from its sampled channels, filtered as the
!! regulations prescribe: HIC15 and HIC36 of the head resultant acceleration
!! (CFC 1000), Nij in its four modes at the occipital condyle (CFC 600), NIC
!! (CFC 60), and the peak upper-neck tension, compression, shear and moments
!! (CFC 600). Limits from reference/reference-data.md.
module hn_assessment
    use hn_kinds, only: wp, zero, g_std
    use hn_filters, only: cfc_filter
    use hn_injury, only: hic, nij, nic, nij_intercepts_t
    implicit none
    private

    public :: assessment_t, assess, criteria_channels

    !> The channels the assessment reads, in this order.
    character(len=8), parameter :: criteria_channels(7) = [character(len=8) :: 'HEAD_AX', 'HEAD_AY', 'HEAD_AZ', &
                                                           'T1_AX', 'OC_FX', 'OC_FZ', 'OC_MY']

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
        real(wp), allocatable :: head_ar(:)                        !! CFC 1000 resultant [g]
        real(wp), allocatable :: nij_t(:, :)                       !! (nt, 4) Nij modes
        real(wp), allocatable :: nic_t(:)                          !! NIC [m^2/s^2]
        real(wp), allocatable :: fx(:), fz(:), my(:)               !! CFC 600 OC loads
    end type assessment_t

contains

    !> Assess from samples every dt [s] starting at t0; hist(:, k) is
    !! criteria_channels(k) (accelerations in g, loads in N and N m).
    subroutine assess(t0, dt, hist, a)
        real(wp), intent(in) :: t0, dt
        real(wp), intent(in) :: hist(:, :)
        type(assessment_t), intent(out) :: a
        real(wp), allocatable :: ax(:), ay(:), az(:), t1x(:)
        type(nij_intercepts_t) :: crit
        integer :: n, m, k
        n = size(hist, 1)
        if (n < 3) then
            a%note = 'not computed: fewer than 3 samples'
            return
        end if
        if (dt > 1.0e-4_wp*(1 + 1.0e-9_wp)) then
            a%note = 'not computed: the HDF5 sampling is coarser than 0.1 ms (10 kHz), needed for CFC 1000 and 600'
            return
        end if
        a%computed = .true.
        allocate (ax(n), ay(n), az(n), t1x(n), a%head_ar(n), a%nij_t(n, 4), a%nic_t(n), a%fx(n), a%fz(n), a%my(n))
        call cfc_filter(hist(:, 1), dt, 1000.0_wp, ax)
        call cfc_filter(hist(:, 2), dt, 1000.0_wp, ay)
        call cfc_filter(hist(:, 3), dt, 1000.0_wp, az)
        a%head_ar = sqrt(ax**2 + ay**2 + az**2)
        call hic(a%head_ar, dt, 0.015_wp, a%hic15, a%hic15_t1, a%hic15_t2)
        call hic(a%head_ar, dt, 0.036_wp, a%hic36, a%hic36_t1, a%hic36_t2)
        a%hic15_t1 = a%hic15_t1 + t0; a%hic15_t2 = a%hic15_t2 + t0
        a%hic36_t1 = a%hic36_t1 + t0; a%hic36_t2 = a%hic36_t2 + t0

        call cfc_filter(hist(:, 5), dt, 600.0_wp, a%fx)
        call cfc_filter(hist(:, 6), dt, 600.0_wp, a%fz)
        call cfc_filter(hist(:, 7), dt, 600.0_wp, a%my)
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

        call cfc_filter(hist(:, 1)*g_std, dt, 60.0_wp, ax)
        call cfc_filter(hist(:, 4)*g_std, dt, 60.0_wp, t1x)
        call nic(t1x, ax, dt, a%nic_t)
        m = maxloc(a%nic_t, dim=1)
        a%nic_max = a%nic_t(m)
        a%nic_time = t0 + (m - 1)*dt
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
