!> Output channels of a run: named scalar time histories computed from the
!! state of the last dynamics evaluation -- head kinematics, T1 motion,
!! occipital-condyle loads, joint rotations, element forces and the energy
!! balance.
!!
!! Every channel is one descriptor (name, unit, listing group, and how it is
!! computed: a quantity code with an item and a component); the fixed
!! channels are one table below, the per-body and per-element channels are
!! made by one loop over the bodies and one over the element families (each
!! family's `channels` binding names its channels; their values are the
!! family's outputs). Adding a channel of an existing quantity is one
!! line; a new quantity is one line in the table plus one case in
!! `channel_value`. Other code finds channels by name (`channel_index`).
!!
!! Occipital-condyle (OC) loads are those the head exerts on the neck at the
!! head's joint point, in head axes: the negative of the head's section load
!! (hn_sections, the subtree's Newton-Euler balance); tension (Fz) and
!! flexion (My) positive. A LOADCELL card's channels are the section load of
!! its body, in its frame body's axes and in SAE J211 axes.
!!
!! The head accelerometer channels (HEAD_AXS ...) are what an accelerometer
!! at the head's mass centre reads: the specific force a - g in head axes
!! (at rest upright, +1 g along the head's z).
!!
!! The three-dimensional kinematics relative to T1 (head relative to T1 and
!! to R as Bryant angles and rotation vectors, the head's translation in
!! T1's axes, T1's lateral motion, each joint's planar angles) are written to
!! the result file only (`listed` false): the listing keeps its tables.
module hn_channels
    use hn_kinds, only: wp, zero, g_std, deg
    use hn_case, only: case_t
    use hn_dynamics, only: dyn_workspace_t, energy_t
    use hn_kinematics, only: body_accelerations
    use hn_sections, only: section_load, section_point
    use hn_head_angles, only: bryant_angles, bryant_angles_near, planar_angles
    use hn_rotation, only: rotation_vector
    use hn_element_family, only: family_channel_t
    implicit none
    private

    public :: channel_t, channel_set_t, channels_define, channels_compute, channels_start, channel_index

    integer, parameter, public :: chname_len = 24   !! longest channel name
    integer, parameter :: units_len = 12, group_len = 16

    ! what a channel computes (item and component say which body, element or axis)
    integer, parameter :: q_head_acc = 1      !! head mass-centre acceleration, global axis `comp` [g]
    integer, parameter :: q_head_acc_res = 2  !! head resultant acceleration [g]
    integer, parameter :: q_head_acc_loc = 3  !! head acceleration in head axis `comp` [g]
    integer, parameter :: q_head_alpha = 4    !! head angular acceleration, global axis `comp` [rad/s^2]
    integer, parameter :: q_head_omega = 5    !! head angular velocity, global axis `comp` [rad/s]
    integer, parameter :: q_head_pitch = 6    !! head sagittal rotation from its rotation matrix [deg]
    integer, parameter :: q_head_disp = 7     !! head mass centre relative to T1's translation, axis `comp` [mm]
    integer, parameter :: q_t1_acc = 8        !! T1 mass-centre acceleration, global axis `comp` [g]
    integer, parameter :: q_t1_pitch = 9      !! T1 sagittal rotation [deg]
    integer, parameter :: q_t1_disp = 10      !! T1 displacement from its start, global axis `comp` [mm]
    integer, parameter :: q_oc_force = 11     !! head-on-neck force at the OC, head axis `comp` [N]
    integer, parameter :: q_oc_moment = 12    !! head-on-neck moment at the OC, head axis `comp` [N m]
    integer, parameter :: q_joint_rot = 13    !! Bryant angle `comp` (4..6) of body `item` [deg]
    integer, parameter :: q_element = 14      !! output `comp` of element `item` of family `family`
    integer, parameter :: q_energy = 18       !! energy term `comp` (e_* below) [J]
    integer, parameter :: q_rel_bryant = 20   !! Bryant angle `comp` of rotation `item` (r_* below) [deg]
    integer, parameter :: q_rel_rotvec = 21   !! rotation-vector component `comp` of rotation `item` [deg]
    integer, parameter :: q_rel_disp = 22     !! point `item` (1 head mass centre, 2 OC) relative to T1, T1 axis `comp`, from the start [mm]
    integer, parameter :: q_t1_planar = 23    !! T1's planar angle about global axis `comp` [deg]
    integer, parameter :: q_seg_planar = 24   !! planar angle about axis `comp` of body `item` relative to its parent [deg]
    integer, parameter :: q_cell = 25         !! load-cell `item`, component `comp` (1-6 body axes F, M; 7-12 J211) [N, N m]
    integer, parameter :: q_head_acc_sf = 26  !! head accelerometer: specific force a - g in head axis `comp` [g]

    integer, parameter :: r_head_t1 = 1, r_head_lab = 2   !! the two rotations of q_rel_*: head in T1's axes, head in R

    integer, parameter :: e_kinetic = 1, e_gravity = 2, e_elastic = 3, e_hold = 4, e_dissip = 5, &
                          e_muscle = 6, e_applied = 7, e_prescribed = 8, e_balance = 9

    !> One channel: its name, unit, listing group and how it is computed.
    type :: channel_t
        character(len=chname_len) :: name = ''
        character(len=units_len) :: units = ''
        character(len=group_len) :: group = ''
        integer :: quantity = 0   !! a q_* code
        integer :: item = 0       !! body or element number, where the quantity needs one
        integer :: comp = 0       !! axis, resultant or term number, where the quantity needs one
        integer :: family = 0     !! element family (q_element)
        logical :: listed = .true. !! in the listing's tables and peaks (else the result file only)
    end type channel_t

    !> The channels of a run and their current values.
    type :: channel_set_t
        integer :: n = 0
        type(channel_t), allocatable :: list(:)
        character(len=chname_len), allocatable :: name(:)   !! list%name, for lookups and writers
        character(len=units_len), allocatable :: units(:)   !! list%units
        character(len=group_len), allocatable :: group(:)   !! list%group
        logical, allocatable :: listed(:)                   !! list%listed
        real(wp), allocatable :: value(:)
        real(wp) :: head_r0(3) = zero      !! head mass centre relative to T1's origin at the start [m]
        real(wp) :: t1_r0(3) = zero        !! T1's mass centre at the start [m]
        real(wp) :: e0 = zero              !! total energy at the start [J]
        real(wp) :: rel0(3, 2) = zero      !! head mass centre and OC relative to T1 in T1's axes at the start [m]
        real(wp) :: angles(3, 2) = zero    !! Bryant angles of the head in T1 and in R at the last evaluation [rad]
        logical :: started = .false.       !! channels_start has run (angles continue from the last values)
        !> head and T1 mass-centre accelerations along the head's x axis [g]
        !! (NIC in head axes; not channels)
        real(wp) :: head_x_acc(2) = zero
    end type channel_set_t

    !> The fixed channels, in listing order.
    type(channel_t), parameter :: fixed_channels(*) = [ &
        channel_t('HEAD_AX', 'g', 'HEAD', q_head_acc, 0, 1), &
        channel_t('HEAD_AZ', 'g', 'HEAD', q_head_acc, 0, 3), &
        channel_t('HEAD_AR', 'g', 'HEAD', q_head_acc_res, 0, 0), &
        channel_t('HEAD_ALPHY', 'rad/s^2', 'HEAD', q_head_alpha, 0, 2), &
        channel_t('HEAD_OMEGY', 'rad/s', 'HEAD', q_head_omega, 0, 2), &
        channel_t('HEAD_THETY', 'deg', 'HEAD', q_head_pitch, 0, 0), &
        channel_t('HEAD_DX', 'mm', 'HEAD', q_head_disp, 0, 1), &
        channel_t('HEAD_DZ', 'mm', 'HEAD', q_head_disp, 0, 3), &
        channel_t('HEAD_AY', 'g', 'HEAD 3D', q_head_acc, 0, 2), &
        channel_t('HEAD_AXL', 'g', 'HEAD 3D', q_head_acc_loc, 0, 1), &
        channel_t('HEAD_AYL', 'g', 'HEAD 3D', q_head_acc_loc, 0, 2), &
        channel_t('HEAD_AZL', 'g', 'HEAD 3D', q_head_acc_loc, 0, 3), &
        channel_t('HEAD_ALPHX', 'rad/s^2', 'HEAD 3D', q_head_alpha, 0, 1), &
        channel_t('HEAD_ALPHZ', 'rad/s^2', 'HEAD 3D', q_head_alpha, 0, 3), &
        channel_t('HEAD_OMEGX', 'rad/s', 'HEAD 3D', q_head_omega, 0, 1), &
        channel_t('HEAD_OMEGZ', 'rad/s', 'HEAD 3D', q_head_omega, 0, 3), &
        channel_t('HEAD_DY', 'mm', 'HEAD 3D', q_head_disp, 0, 2), &
        channel_t('T1_AX', 'g', 'T1', q_t1_acc, 0, 1), &
        channel_t('T1_AZ', 'g', 'T1', q_t1_acc, 0, 3), &
        channel_t('T1_THETY', 'deg', 'T1', q_t1_pitch, 0, 0), &
        channel_t('T1_DX', 'mm', 'T1', q_t1_disp, 0, 1), &
        channel_t('OC_FX', 'N', 'OC LOADS', q_oc_force, 0, 1), &
        channel_t('OC_FY', 'N', 'OC LOADS', q_oc_force, 0, 2), &
        channel_t('OC_FZ', 'N', 'OC LOADS', q_oc_force, 0, 3), &
        channel_t('OC_MX', 'N m', 'OC LOADS', q_oc_moment, 0, 1), &
        channel_t('OC_MY', 'N m', 'OC LOADS', q_oc_moment, 0, 2), &
        channel_t('OC_MZ', 'N m', 'OC LOADS', q_oc_moment, 0, 3), &
        channel_t('HEAD_AXS', 'g', 'HEAD 3D', q_head_acc_sf, 0, 1, 0, .false.), &
        channel_t('HEAD_AYS', 'g', 'HEAD 3D', q_head_acc_sf, 0, 2, 0, .false.), &
        channel_t('HEAD_AZS', 'g', 'HEAD 3D', q_head_acc_sf, 0, 3, 0, .false.)]

    !> Three-dimensional kinematics relative to T1 and T1's lateral motion
    !! (result file only).
    type(channel_t), parameter :: relative_channels(*) = [ &
        channel_t('HT1_RX', 'deg', 'HEAD-T1 3D', q_rel_bryant, r_head_t1, 1, 0, .false.), &
        channel_t('HT1_RY', 'deg', 'HEAD-T1 3D', q_rel_bryant, r_head_t1, 2, 0, .false.), &
        channel_t('HT1_RZ', 'deg', 'HEAD-T1 3D', q_rel_bryant, r_head_t1, 3, 0, .false.), &
        channel_t('HT1_VX', 'deg', 'HEAD-T1 3D', q_rel_rotvec, r_head_t1, 1, 0, .false.), &
        channel_t('HT1_VY', 'deg', 'HEAD-T1 3D', q_rel_rotvec, r_head_t1, 2, 0, .false.), &
        channel_t('HT1_VZ', 'deg', 'HEAD-T1 3D', q_rel_rotvec, r_head_t1, 3, 0, .false.), &
        channel_t('HT1_DX', 'mm', 'HEAD-T1 3D', q_rel_disp, 1, 1, 0, .false.), &
        channel_t('HT1_DY', 'mm', 'HEAD-T1 3D', q_rel_disp, 1, 2, 0, .false.), &
        channel_t('HT1_DZ', 'mm', 'HEAD-T1 3D', q_rel_disp, 1, 3, 0, .false.), &
        channel_t('OCT1_DX', 'mm', 'HEAD-T1 3D', q_rel_disp, 2, 1, 0, .false.), &
        channel_t('OCT1_DY', 'mm', 'HEAD-T1 3D', q_rel_disp, 2, 2, 0, .false.), &
        channel_t('OCT1_DZ', 'mm', 'HEAD-T1 3D', q_rel_disp, 2, 3, 0, .false.), &
        channel_t('HEADL_RX', 'deg', 'HEAD-LAB 3D', q_rel_bryant, r_head_lab, 1, 0, .false.), &
        channel_t('HEADL_RY', 'deg', 'HEAD-LAB 3D', q_rel_bryant, r_head_lab, 2, 0, .false.), &
        channel_t('HEADL_RZ', 'deg', 'HEAD-LAB 3D', q_rel_bryant, r_head_lab, 3, 0, .false.), &
        channel_t('HEADL_VX', 'deg', 'HEAD-LAB 3D', q_rel_rotvec, r_head_lab, 1, 0, .false.), &
        channel_t('HEADL_VY', 'deg', 'HEAD-LAB 3D', q_rel_rotvec, r_head_lab, 2, 0, .false.), &
        channel_t('HEADL_VZ', 'deg', 'HEAD-LAB 3D', q_rel_rotvec, r_head_lab, 3, 0, .false.), &
        channel_t('T1_AY', 'g', 'T1 3D', q_t1_acc, 0, 2, 0, .false.), &
        channel_t('T1_DY', 'mm', 'T1 3D', q_t1_disp, 0, 2, 0, .false.), &
        channel_t('T1_DZ', 'mm', 'T1 3D', q_t1_disp, 0, 3, 0, .false.), &
        channel_t('T1_THETX', 'deg', 'T1 3D', q_t1_planar, 0, 1, 0, .false.), &
        channel_t('T1_THETZ', 'deg', 'T1 3D', q_t1_planar, 0, 3, 0, .false.)]

    !> The components of a load cell's channels: name suffix and unit.
    character(len=4), parameter :: cell_suffix(12) = [character(len=4) :: '_FX', '_FY', '_FZ', '_MX', '_MY', '_MZ', &
                                                      '_JFX', '_JFY', '_JFZ', '_JMX', '_JMY', '_JMZ']

    !> The energy channels, last in the list.
    type(channel_t), parameter :: energy_channels(*) = [ &
        channel_t('E_KINETIC', 'J', 'ENERGY', q_energy, 0, e_kinetic), &
        channel_t('E_GRAVITY', 'J', 'ENERGY', q_energy, 0, e_gravity), &
        channel_t('E_ELASTIC', 'J', 'ENERGY', q_energy, 0, e_elastic), &
        channel_t('E_HOLD', 'J', 'ENERGY', q_energy, 0, e_hold), &
        channel_t('E_DISSIP', 'J', 'ENERGY', q_energy, 0, e_dissip), &
        channel_t('E_MUSCLE', 'J', 'ENERGY', q_energy, 0, e_muscle), &
        channel_t('W_APPLIED', 'J', 'ENERGY', q_energy, 0, e_applied), &
        channel_t('W_PRESCR', 'J', 'ENERGY', q_energy, 0, e_prescribed), &
        channel_t('E_BALANCE', 'J', 'ENERGY', q_energy, 0, e_balance)]

    character(len=2), parameter :: coord_names(6) = ['TX', 'TY', 'TZ', 'RX', 'RY', 'RZ']

    !> Head and T1 quantities shared by several channels at one instant.
    type :: head_state_t
        real(wp) :: s(3, 3) = zero         !! head rotation matrix (head axes -> R)
        real(wp) :: angles(3, 2) = zero    !! Bryant angles of the head in T1's axes and in R [rad]
        real(wp) :: rotvec(3, 2) = zero    !! rotation vectors of the same [rad]
        real(wp) :: rel(3, 2) = zero       !! head mass centre and OC relative to T1, T1's axes, from the start [m]
        real(wp), allocatable :: cell(:, :) !! (12, ncell) load-cell loads: body axes F, M; J211 F, M [N, N m]
        real(wp) :: acc(3) = zero          !! head mass-centre acceleration [m/s^2]
        real(wp) :: alpha(3) = zero        !! head angular acceleration [rad/s^2]
        real(wp) :: disp(3) = zero         !! head mass centre relative to T1's translation [m]
        real(wp) :: t1_acc(3) = zero       !! T1 mass-centre acceleration [m/s^2]
        real(wp) :: oc_force(3) = zero     !! head on neck at the OC, head axes [N]
        real(wp) :: oc_moment(3) = zero    !! head on neck at the OC, head axes [N m]
    end type head_state_t

contains

    !> The channel list of a case; with `only`, just the channels named
    !! there (a calibration member's rated channels).
    subroutine channels_define(cs, ch, only)
        type(case_t), intent(in) :: cs          !! the case (its model's bodies and elements)
        type(channel_set_t), intent(out) :: ch  !! the channels, values zero
        character(len=*), intent(in), optional :: only(:)  !! the only channels wanted (by name; kept in the set's order)
        type(channel_t), allocatable :: c(:)
        type(family_channel_t), allocatable :: fc(:)
        integer :: k, e, m, n, f
        associate (model => cs%model, tree => cs%model%tree)
            n = size(fixed_channels) + size(relative_channels) + 12*ncells(cs) + 6*(tree%nbody - 1) &
                + size(energy_channels)
            allocate (c(n))
            n = size(fixed_channels)
            c(1:n) = fixed_channels
            c(n + 1:n + size(relative_channels)) = relative_channels
            n = n + size(relative_channels)
            do k = 1, ncells(cs)
                do m = 1, 12
                    call add(channel_t(trim(cs%loadcells(k)%name)//cell_suffix(m), merge('N  ', 'N m', mod(m - 1, 6) < 3), &
                                       merge('LOADCELL ', 'J211     ', m <= 6)//cs%loadcells(k)%name, q_cell, k, m))
                end do
            end do
            do m = 4, 6
                do k = 1, tree%nbody
                    if (tree%parent(k) == 0) cycle
                    call add(channel_t(trim(tree%name(k))//'_'//coord_names(m), 'deg', 'JOINTS '//coord_names(m), &
                                       q_joint_rot, k, m))
                end do
            end do
            do m = 1, 3
                do k = 1, tree%nbody
                    if (tree%parent(k) == 0) cycle
                    call add(channel_t(trim(tree%name(k))//'_P'//coord_names(m)(2:2), 'deg', 'PLANES '//coord_names(m + 3), &
                                       q_seg_planar, k, m, 0, .false.))
                end do
            end do
            do f = 1, size(model%family)
                fc = model%family(f)%f%channels(tree)
                c = [c(1:n), [(channel_t(fc(e)%name, fc(e)%units, fc(e)%group, q_element, fc(e)%item, fc(e)%comp, f), &
                              e=1, size(fc))], c(n + 1:)]
                n = n + size(fc)
            end do
        end associate
        c(n + 1:) = energy_channels
        if (present(only)) c = pack(c, [(any(only == c(k)%name), k=1, size(c))])
        ch%n = size(c)
        ch%list = c
        ch%name = c%name
        ch%units = c%units
        ch%group = c%group
        ch%listed = c%listed
        allocate (ch%value(ch%n))
        ch%value = zero
    contains
        subroutine add(one)
            type(channel_t), intent(in) :: one
            n = n + 1
            c(n) = one
        end subroutine add
    end subroutine channels_define

    !> Number of load cells of a case.
    pure integer function ncells(cs) result(n)
        type(case_t), intent(in) :: cs
        n = 0
        if (allocated(cs%loadcells)) n = size(cs%loadcells)
    end function ncells

    !> The start values the channels relative to the start subtract (T1's
    !! position, the head's relative to T1, energy aside), from the workspace
    !! of the evaluation at the start; the angles' continuation begins here.
    pure subroutine channels_start(cs, ws, ch)
        type(case_t), intent(in) :: cs               !! the case
        type(dyn_workspace_t), intent(in) :: ws      !! workspace of the evaluation at the start
        type(channel_set_t), intent(inout) :: ch     !! start values set
        real(wp) :: st(3, 3)
        associate (kin => ws%kin, h => cs%head, t1 => cs%t1)
            ch%head_r0 = kin%r(:, h) - kin%r(:, t1)
            ch%t1_r0 = kin%r(:, t1)
            st = transpose(kin%s(:, :, t1))
            ch%rel0(:, 1) = matmul(st, kin%r(:, h) - kin%r(:, t1))
            ch%rel0(:, 2) = matmul(st, kin%joint(:, h) - kin%r(:, t1))
            ch%angles(:, r_head_t1) = bryant_angles(matmul(st, kin%s(:, :, h)))
            ch%angles(:, r_head_lab) = bryant_angles(kin%s(:, :, h))
        end associate
        ch%started = .true.
    end subroutine channels_start

    !> Index of the channel called `name` in the set, 0 when there is none.
    pure integer function channel_index(ch, name) result(k)
        type(channel_set_t), intent(in) :: ch   !! the channel set
        character(len=*), intent(in) :: name    !! a channel name
        k = findloc(ch%name, name, dim=1)
    end function channel_index

    !> Channel values at time t from the workspace of the evaluation at t
    !! (kinematics, accelerations, element outputs) and the energy terms.
    subroutine channels_compute(cs, ws, t, en, ch)
        type(case_t), intent(in) :: cs               !! the case
        type(dyn_workspace_t), intent(in) :: ws      !! workspace of the evaluation at t
        real(wp), intent(in) :: t                    !! time [s]
        type(energy_t), intent(in) :: en             !! energy terms at t
        type(channel_set_t), intent(inout) :: ch     !! values updated
        type(head_state_t) :: hs
        integer :: k
        hs = head_state(cs, ws, t, ch)
        if (ch%started) ch%angles = hs%angles
        ch%head_x_acc = [dot_product(hs%s(:, 1), hs%acc), dot_product(hs%s(:, 1), hs%t1_acc)]/g_std
        do k = 1, ch%n
            ch%value(k) = channel_value(ch%list(k), cs, ws, hs, en, ch)
        end do
    end subroutine channels_compute

    !> The value of one channel.
    pure real(wp) function channel_value(c, cs, ws, hs, en, ch) result(v)
        type(channel_t), intent(in) :: c
        type(case_t), intent(in) :: cs
        type(dyn_workspace_t), intent(in) :: ws
        type(head_state_t), intent(in) :: hs
        type(energy_t), intent(in) :: en
        type(channel_set_t), intent(in) :: ch
        real(wp) :: sl(3), q(3)
        integer :: j
        associate (model => cs%model, h => cs%head, t1 => cs%t1)
            select case (c%quantity)
            case (q_head_acc); v = hs%acc(c%comp)/g_std
            case (q_head_acc_res); v = norm2(hs%acc)/g_std
            case (q_head_acc_loc, q_head_acc_sf)   ! in head axes: a, or an accelerometer's a - g
                sl = matmul(transpose(hs%s), hs%acc - merge(model%gravity, [zero, zero, zero], &
                                                            c%quantity == q_head_acc_sf))/g_std
                v = sl(c%comp)
            case (q_head_alpha); v = hs%alpha(c%comp)
            case (q_head_omega); v = ws%kin%omega(c%comp, h)
            case (q_head_pitch); v = atan2(hs%s(1, 3), hs%s(3, 3))/deg
            case (q_head_disp); v = 1000*hs%disp(c%comp)
            case (q_t1_acc); v = hs%t1_acc(c%comp)/g_std
            case (q_t1_pitch); v = atan2(ws%kin%s(1, 3, t1), ws%kin%s(3, 3, t1))/deg
            case (q_t1_disp); v = 1000*(ws%kin%r(c%comp, t1) - ch%t1_r0(c%comp))
            case (q_oc_force); v = hs%oc_force(c%comp)
            case (q_oc_moment); v = hs%oc_moment(c%comp)
            case (q_joint_rot)
                j = model%tree%dof_index(c%comp, c%item)
                if (j > 0) then
                    v = ws%x(j)/deg
                else
                    v = model%tree%q_ref(c%comp, c%item)/deg
                end if
            case (q_element); v = merge(ws%eo%fam(c%family)%v(c%comp, c%item), zero, model%family_on(c%family))
            case (q_energy); v = energy_value(en, c%comp, ch%e0)
            case (q_rel_bryant); v = hs%angles(c%comp, c%item)/deg
            case (q_rel_rotvec); v = hs%rotvec(c%comp, c%item)/deg
            case (q_rel_disp); v = 1000*hs%rel(c%comp, c%item)
            case (q_t1_planar)
                q = planar_angles(ws%kin%s(:, :, t1))
                v = q(c%comp)/deg
            case (q_seg_planar)
                q = planar_angles(matmul(transpose(ws%kin%s(:, :, model%tree%parent(c%item))), ws%kin%s(:, :, c%item)))
                v = q(c%comp)/deg
            case (q_cell); v = hs%cell(c%comp, c%item)
            case default; v = zero
            end select
        end associate
    end function channel_value

    !> Energy term `which` (e_* codes); the balance relative to the start.
    pure real(wp) function energy_value(en, which, e0) result(v)
        type(energy_t), intent(in) :: en
        integer, intent(in) :: which
        real(wp), intent(in) :: e0
        select case (which)
        case (e_kinetic); v = en%kinetic
        case (e_gravity); v = en%gravity
        case (e_elastic); v = en%elastic
        case (e_hold); v = en%hold
        case (e_dissip); v = en%dissipated
        case (e_muscle); v = en%muscle
        case (e_applied); v = en%applied
        case (e_prescribed); v = en%prescribed
        case default; v = en%total - e0
        end select
    end function energy_value

    !> Head and T1 accelerations, the occipital-condyle loads (the negative of
    !! the head's section load at its joint point, in head axes), the head's
    !! rotation and position relative to T1 and R, and the load cells'
    !! section loads (body axes and J211 axes).
    pure function head_state(cs, ws, t, ch) result(hs)
        type(case_t), intent(in) :: cs
        type(dyn_workspace_t), intent(in) :: ws
        real(wp), intent(in) :: t
        type(channel_set_t), intent(in) :: ch
        type(head_state_t) :: hs
        real(wp) :: acc(3, cs%model%tree%nbody), alpha(3, cs%model%tree%nbody)
        real(wp) :: f(3), mo(3), st(3, 3), rh(3, 3), sb(3, 3)
        real(wp), parameter :: j211(3) = [1.0_wp, -1.0_wp, -1.0_wp]   ! hhneck axes -> SAE J211 axes
        integer :: h, k, b
        h = cs%head
        call body_accelerations(cs%model%tree, ws%kin, ws%xdd, acc, alpha)
        hs%s = ws%kin%s(:, :, h)
        hs%acc = acc(:, h)
        hs%alpha = alpha(:, h)
        hs%t1_acc = acc(:, cs%t1)
        hs%disp = ws%kin%r(:, h) - ws%kin%r(:, cs%t1) - ch%head_r0
        call section_load(cs%model, ws%kin, acc, alpha, t, h, ws%kin%joint(:, h), f, mo)
        hs%oc_force = -matmul(transpose(hs%s), f)            ! head on neck, head axes
        hs%oc_moment = -matmul(transpose(hs%s), mo)
        st = transpose(ws%kin%s(:, :, cs%t1))
        rh = matmul(st, hs%s)
        if (ch%started) then
            hs%angles(:, r_head_t1) = bryant_angles_near(rh, ch%angles(:, r_head_t1))
            hs%angles(:, r_head_lab) = bryant_angles_near(hs%s, ch%angles(:, r_head_lab))
        else
            hs%angles(:, r_head_t1) = bryant_angles(rh)
            hs%angles(:, r_head_lab) = bryant_angles(hs%s)
        end if
        hs%rotvec(:, r_head_t1) = rotation_vector(rh)
        hs%rotvec(:, r_head_lab) = rotation_vector(hs%s)
        hs%rel(:, 1) = matmul(st, ws%kin%r(:, h) - ws%kin%r(:, cs%t1)) - ch%rel0(:, 1)
        hs%rel(:, 2) = matmul(st, ws%kin%joint(:, h) - ws%kin%r(:, cs%t1)) - ch%rel0(:, 2)
        allocate (hs%cell(12, ncells(cs)))
        do k = 1, ncells(cs)
            b = cs%loadcells(k)%body
            call section_load(cs%model, ws%kin, acc, alpha, t, b, section_point(ws%kin, cs%loadcells(k)), f, mo)
            sb = transpose(ws%kin%s(:, :, cs%loadcells(k)%frame))
            hs%cell(1:3, k) = matmul(sb, f)
            hs%cell(4:6, k) = matmul(sb, mo)
            hs%cell(7:9, k) = j211*hs%cell(1:3, k)
            hs%cell(10:12, k) = j211*hs%cell(4:6, k)
        end do
    end function head_state

end module hn_channels
