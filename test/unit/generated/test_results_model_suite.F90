!> The element tables of the result file (/model/elements, hn_results_model):
!! a two-link model with a spring to R, a ligament, no muscles and a tilted
!! disc is written and read back; the values are the ones set here, the
!! lower plate frame that of the tilt, every dataset has its units.
module test_results_model
    use funit
    use hn_kinds, only: wp, msglen
    use hn_tree, only: body_tree_t, tree_allocate, tree_build
    use hn_model, only: model_t, model_init, model_set_neutral
    use hn_line_elements, only: spring_t, ligament_t
    use hn_discs, only: disc_t
    use hn_h5, only: h5_file_t, h5_read_real, h5_dims, h5_read_string_attr
    use hn_results_model, only: write_element_tables
    implicit none

    character(len=*), parameter :: fname = 'test_results_model.h5'
    real(wp), parameter :: tilt = 0.1_wp                         !! disc plate tilt [rad]
    real(wp), parameter :: spring_a(3) = [0.1_wp, 0.2_wp, 0.3_wp]   !! point of R
    real(wp), parameter :: spring_b(3) = [0.01_wp, -0.02_wp, 0.03_wp]
    real(wp), parameter :: lig_a(3) = [0.009_wp, 0.0_wp, 0.0055_wp]
    real(wp), parameter :: lig_b(3) = [-0.04_wp, 0.001_wp, -0.00475_wp]

contains

    !@before
    subroutine write_file()
        type(body_tree_t) :: tree
        type(model_t) :: model
        type(h5_file_t) :: h5
        integer :: stat
        character(len=msglen) :: msg
        call tree_allocate(tree, 2)                  ! a chain R - B1 - B2, unit masses and inertias
        tree%joint_parent(:, 2) = [0.0_wp, 0.0_wp, 0.05_wp]
        tree%joint_child(:, 2) = [0.0_wp, 0.0_wp, -0.05_wp]
        call tree_build(tree, stat, msg)
        call model_init(model, tree)
        model%springs = [spring_t(body_a=0, body_b=2, point_a=spring_a, point_b=spring_b, stiffness=100.0_wp)]
        model%ligaments = [ligament_t(name='LIGX', body_a=1, body_b=2, point_a=lig_a, point_b=lig_b, l1=1.0e3_wp)]
        model%discs = [disc_t(name='D12', body_a=1, body_b=2, pa=[0.0_wp, 0.0_wp, -0.045_wp], &
                              pb=[0.0_wp, 0.0_wp, 0.045_wp], tilt=tilt, area=3.0e-4_wp, h=0.005_wp, &
                              d1=1.0e6_wp, d2=1.0e3_wp, g=1.0e6_wp, ix=1.0e-8_wp, iy=1.0e-8_wp, j=1.0e-8_wp)]
        call model_set_neutral(model)
        call h5%create(fname, stat, msg)
        call h5%group('/model')
        call write_element_tables(h5, model)
        call h5%close(.true., stat, msg)
    end subroutine write_file

    !@after
    subroutine remove_file()
        integer :: u, ios
        open (newunit=u, file=fname, status='old', iostat=ios)
        if (ios == 0) close (u, status='delete')
    end subroutine remove_file

    !@test
    subroutine test_spring_to_R_keeps_body_zero()
        real(wp) :: body(2)
        integer :: stat
        call h5_read_real(fname, '/model/elements/springs/body', body, stat)
#line 61 "/work/main/test/unit/test_results_model.pf"
  call assertEqual([0.0_wp, 2.0_wp], body, 'spring bodies: R (0), then body 2', &
 & location=SourceLocation( &
 & 'test_results_model.pf', &
 & 61) )
  if (anyExceptions()) return
#line 62 "/work/main/test/unit/test_results_model.pf"
    end subroutine test_spring_to_R_keeps_body_zero

    !@test
    subroutine test_spring_points_as_given()
        real(wp) :: p(3, 2)
        integer :: stat
        call h5_read_real(fname, '/model/elements/springs/point', p, stat)
#line 69 "/work/main/test/unit/test_results_model.pf"
  call assertEqual(spring_a, p(:, 1), 'end a: a point of R', &
 & location=SourceLocation( &
 & 'test_results_model.pf', &
 & 69) )
  if (anyExceptions()) return
#line 70 "/work/main/test/unit/test_results_model.pf"
#line 70 "/work/main/test/unit/test_results_model.pf"
  call assertEqual(spring_b, p(:, 2), 'end b: body-2 frame', &
 & location=SourceLocation( &
 & 'test_results_model.pf', &
 & 70) )
  if (anyExceptions()) return
#line 71 "/work/main/test/unit/test_results_model.pf"
    end subroutine test_spring_points_as_given

    !@test
    subroutine test_ligament_bodies_and_points_as_given()
        real(wp) :: body(2), p(3, 2)
        integer :: stat
        call h5_read_real(fname, '/model/elements/ligaments/body', body, stat)
        call h5_read_real(fname, '/model/elements/ligaments/point', p, stat)
#line 79 "/work/main/test/unit/test_results_model.pf"
  call assertEqual([1.0_wp, 2.0_wp], body, 'ligament bodies 1 and 2', &
 & location=SourceLocation( &
 & 'test_results_model.pf', &
 & 79) )
  if (anyExceptions()) return
#line 80 "/work/main/test/unit/test_results_model.pf"
#line 80 "/work/main/test/unit/test_results_model.pf"
  call assertEqual(reshape([lig_a, lig_b], [3, 2]), p, 'ligament points a, b', &
 & location=SourceLocation( &
 & 'test_results_model.pf', &
 & 80) )
  if (anyExceptions()) return
#line 81 "/work/main/test/unit/test_results_model.pf"
    end subroutine test_ligament_bodies_and_points_as_given

    !@test
    subroutine test_lower_plate_frame_is_the_tilt_about_y()
        real(wp) :: r(3, 3, 2), want(3, 3)
        integer :: stat
        call h5_read_real(fname, '/model/elements/discs/plate_frame', r, stat)
        want = 0.0_wp                                  ! right-handed rotation about y by the tilt
        want(1, 1) = cos(tilt); want(1, 3) = sin(tilt)
        want(2, 2) = 1.0_wp
        want(3, 1) = -sin(tilt); want(3, 3) = cos(tilt)
#line 92 "/work/main/test/unit/test_results_model.pf"
  call assertEqual(want, r(:, :, 1), 10*epsilon(1.0_wp), 'lower plate frame R_ij in the lower body', &
 & location=SourceLocation( &
 & 'test_results_model.pf', &
 & 92) )
  if (anyExceptions()) return
#line 93 "/work/main/test/unit/test_results_model.pf"
    end subroutine test_lower_plate_frame_is_the_tilt_about_y

    !@test
    subroutine test_family_without_elements_has_zero_rows()
        integer, allocatable :: dims(:)
        integer :: stat
        call h5_dims(fname, '/model/elements/muscles/point', dims, stat)
#line 100 "/work/main/test/unit/test_results_model.pf"
  call assertEqual(0, stat, 'muscles/point exists', &
 & location=SourceLocation( &
 & 'test_results_model.pf', &
 & 100) )
  if (anyExceptions()) return
#line 101 "/work/main/test/unit/test_results_model.pf"
#line 101 "/work/main/test/unit/test_results_model.pf"
  call assertEqual([3, 2, 0], dims, 'muscles/point: 0 elements (Fortran order)', &
 & location=SourceLocation( &
 & 'test_results_model.pf', &
 & 101) )
  if (anyExceptions()) return
#line 102 "/work/main/test/unit/test_results_model.pf"
    end subroutine test_family_without_elements_has_zero_rows

    !@test
    subroutine test_every_dataset_has_units()
        character(len=*), parameter :: fam(4) = [character(len=9) :: 'ligaments', 'muscles', 'springs', 'discs']
        character(len=*), parameter :: ds(3) = [character(len=5) :: 'name', 'body', 'point']
        character(len=*), parameter :: disc_ds(3) = [character(len=11) :: 'plate_frame', 'area', 'thickness']
        character(len=40) :: units
        integer :: f, d, stat
        do f = 1, size(fam)
            do d = 1, size(ds)
                call h5_read_string_attr(fname, '/model/elements/'//trim(fam(f))//'/'//trim(ds(d)), 'units', units, stat)
#line 114 "/work/main/test/unit/test_results_model.pf"
  call assertTrue(stat == 0 .and. len_trim(units) > 0, trim(fam(f))//'/'//trim(ds(d))//' has units', &
 & location=SourceLocation( &
 & 'test_results_model.pf', &
 & 114) )
  if (anyExceptions()) return
#line 115 "/work/main/test/unit/test_results_model.pf"
            end do
        end do
        do d = 1, size(disc_ds)
            call h5_read_string_attr(fname, '/model/elements/discs/'//trim(disc_ds(d)), 'units', units, stat)
#line 119 "/work/main/test/unit/test_results_model.pf"
  call assertTrue(stat == 0 .and. len_trim(units) > 0, 'discs/'//trim(disc_ds(d))//' has units', &
 & location=SourceLocation( &
 & 'test_results_model.pf', &
 & 119) )
  if (anyExceptions()) return
#line 120 "/work/main/test/unit/test_results_model.pf"
        end do
    end subroutine test_every_dataset_has_units

end module test_results_model

module Wraptest_results_model
   use FUnit
   use test_results_model
   implicit none
   private

contains


end module Wraptest_results_model

function test_results_model_suite() result(suite)
   use FUnit
   use test_results_model
   use Wraptest_results_model
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_results_model_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_spring_to_R_keeps_body_zero', &
      test_spring_to_R_keeps_body_zero, setUp=write_file, tearDown=remove_file))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_spring_points_as_given', &
      test_spring_points_as_given, setUp=write_file, tearDown=remove_file))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_ligament_bodies_and_points_as_given', &
      test_ligament_bodies_and_points_as_given, setUp=write_file, tearDown=remove_file))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_lower_plate_frame_is_the_tilt_about_y', &
      test_lower_plate_frame_is_the_tilt_about_y, setUp=write_file, tearDown=remove_file))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_family_without_elements_has_zero_rows', &
      test_family_without_elements_has_zero_rows, setUp=write_file, tearDown=remove_file))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_every_dataset_has_units', &
      test_every_dataset_has_units, setUp=write_file, tearDown=remove_file))
   call suite%addTest(t)


end function test_results_model_suite

