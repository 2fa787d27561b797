!> The cross-checking dump: at requested times, every body's mass,
!! inertia, rotation matrix, mass-centre position, velocity and
!! acceleration, angular velocity and acceleration, and resultant applied
!! force and moment about the mass centre (all in R), with x, xdot, a_ij,
!! f_i and xddot. Layout in docs/output-format.md (group /dump).
module hn_dump
    use hn_kinds, only: wp, msglen
    use hn_status, only: stat_ok
    use hn_model, only: model_t
    use hn_dynamics, only: dyn_workspace_t
    use hn_kinematics, only: body_accelerations
    use hn_kane, only: equivalent_body_loads
    use hn_tree, only: dof_label
    use hn_h5, only: h5_file_t
    implicit none
    private

    public :: dump_open, dump_record

contains

    !> Create group /dump with the constant body tables and empty series,
    !! units on each; `nrec` records are expected (the chunk size).
    subroutine dump_open(h5, model, nrec)
        type(h5_file_t), intent(inout) :: h5   !! the open result file
        type(model_t), intent(in) :: model     !! the model (body tables, coordinates)
        integer, intent(in), optional :: nrec  !! number of dump times
        integer :: nb, n, j, nr
        character(len=32), allocatable :: labels(:)
        nb = model%tree%nbody
        n = model%tree%ndof
        nr = 8
        if (present(nrec)) nr = max(1, nrec)
        call h5%group('/dump')
        call h5%write_real('/dump/mass', model%tree%mass, [nb])
        call h5%attr_string('/dump/mass', 'units', 'kg')
        call h5%write_real('/dump/inertia', model%tree%inertia, [3, 3, nb])
        call h5%attr_string('/dump/inertia', 'units', 'kg m^2')
        call h5%attr_string('/dump/inertia', 'description', 'centroidal inertia matrix in body axes')
        allocate (labels(n))
        do j = 1, n
            labels(j) = dof_label(model%tree, j)
        end do
        call h5%attr_strings('/dump', 'coordinates', labels)
        call series('time', [integer ::], 's')
        call series('rotation', [3, 3, nb], '1')
        call series('position', [3, nb], 'm')
        call series('velocity', [3, nb], 'm/s')
        call series('acceleration', [3, nb], 'm/s^2')
        call series('angular_velocity', [3, nb], 'rad/s')
        call series('angular_acceleration', [3, nb], 'rad/s^2')
        call series('force', [3, nb], 'N')
        call series('moment', [3, nb], 'N m')
        call series('x', [n], 'm or rad (by coordinate)')
        call series('xd', [n], 'm/s or rad/s (by coordinate)')
        call series('xdd', [n], 'm/s^2 or rad/s^2 (by coordinate)')
        call series('f', [n], 'N or N m (by coordinate)')
        call series('a', [n, n], 'kg, kg m or kg m^2 (by coordinate pair)')
    contains
        subroutine series(name, dims, units)
            character(len=*), intent(in) :: name, units
            integer, intent(in) :: dims(:)
            call h5%series('/dump/'//name, dims, nr)
            call h5%attr_string('/dump/'//name, 'units', units)
        end subroutine series
    end subroutine dump_open

    !> Append one record from the workspace of the dynamics evaluation at t.
    subroutine dump_record(h5, model, ws, t, stat, errmsg)
        type(h5_file_t), intent(inout) :: h5           !! the result file with /dump from dump_open
        type(model_t), intent(in) :: model             !! the model (body tree)
        type(dyn_workspace_t), intent(in) :: ws        !! workspace of a full dynamics evaluation at t
        real(wp), intent(in) :: t                      !! time of the record [s]
        integer, intent(out) :: stat                   !! stat_ok, or stat_gimbal (a body's joint couples not resolved)
        character(len=msglen), intent(out) :: errmsg   !! which body's Bryant axes are singular ('' when stat_ok)
        real(wp) :: acc(3, model%tree%nbody), alpha(3, model%tree%nbody)
        real(wp) :: force(3, model%tree%nbody), moment(3, model%tree%nbody)
        integer :: bad_body
        errmsg = ''
        call body_accelerations(model%tree, ws%kin, ws%xdd, acc, alpha)
        call equivalent_body_loads(model%tree, ws%kin, ws%loads, force, moment, stat, bad_body)
        if (stat /= stat_ok) then
            write (errmsg, '(a,es12.5,3a)') 'dump at t = ', t, ' s: Bryant axes of body ', &
                trim(model%tree%name(bad_body)), ' are singular; joint couples cannot be written as body moments'
        end if
        call h5%append('/dump/time', [t])
        call h5%append('/dump/rotation', ws%kin%s)
        call h5%append('/dump/position', ws%kin%r)
        call h5%append('/dump/velocity', ws%kin%v)
        call h5%append('/dump/acceleration', acc)
        call h5%append('/dump/angular_velocity', ws%kin%omega)
        call h5%append('/dump/angular_acceleration', alpha)
        call h5%append('/dump/force', force)
        call h5%append('/dump/moment', moment)
        call h5%append('/dump/x', ws%x)
        call h5%append('/dump/xd', ws%xd)
        call h5%append('/dump/xdd', ws%xdd)
        call h5%append('/dump/f', ws%f)
        call h5%append('/dump/a', ws%a)
    end subroutine dump_record

end module hn_dump
