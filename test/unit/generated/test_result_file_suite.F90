!> The result file tells the truth (issue 14): a missing directory is
!! created, a lock file keeps a second writer off the name (a dead writer's
!! lock is taken over), an older result is removed when a new one starts,
!! a failing HDF5 call is caught with HDF5's reason in one message and the
!! partial file removed, and text attributes read back as written.
module test_result_file
    use funit
    use hn_kinds, only: wp, msglen
    use hn_h5, only: h5_file_t, h5_read_string_attr, h5_read_real, h5_dims
    use hn_posix, only: file_kind, kind_missing, kind_regular, make_directories, remove_file, host_name, &
                        remove_directory
    implicit none

    character(len=*), parameter :: dir = 'test_result_file_dir'

contains

    !> Write the lines to file fname, each ended by LF.
    subroutine write_lines(fname, lines)
        character(len=*), intent(in) :: fname, lines(:)
        integer :: u, k
        open (newunit=u, file=fname, status='replace', form='unformatted', access='stream')
        do k = 1, size(lines)
            write (u) trim(lines(k))//achar(10)
        end do
        close (u)
    end subroutine write_lines

    !> Delete file fname if it exists.
    subroutine delete_file(fname)
        character(len=*), intent(in) :: fname
        integer :: u, ios
        open (newunit=u, file=fname, status='old', iostat=ios)
        if (ios == 0) close (u, status='delete')
    end subroutine delete_file

    logical function exists(path)
        character(len=*), intent(in) :: path
        exists = file_kind(path) /= kind_missing
    end function exists

    !@test
    subroutine test_missing_directory_created_and_file_renamed_when_closed()
        type(h5_file_t) :: h
        integer :: stat
        character(len=msglen) :: msg
        character(len=40) :: text
        real(wp) :: v(3)
        integer, allocatable :: d(:)
        call h%create(dir//'/new/a.h5', stat, msg)
#line 51 "/work/main/test/unit/test_result_file.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 51) )
  if (anyExceptions()) return
#line 52 "/work/main/test/unit/test_result_file.pf"
#line 52 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(index(h%note, 'created directory '//dir//'/new') > 0, trim(h%note), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 52) )
  if (anyExceptions()) return
#line 53 "/work/main/test/unit/test_result_file.pf"
#line 53 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(exists(dir//'/new/a.h5.part'), 'written under .part', &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 53) )
  if (anyExceptions()) return
#line 54 "/work/main/test/unit/test_result_file.pf"
#line 54 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(exists(dir//'/new/a.h5.lock'), 'locked while written', &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 54) )
  if (anyExceptions()) return
#line 55 "/work/main/test/unit/test_result_file.pf"
#line 55 "/work/main/test/unit/test_result_file.pf"
  call assertFalse(exists(dir//'/new/a.h5'), 'no final name before closing', &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 55) )
  if (anyExceptions()) return
#line 56 "/work/main/test/unit/test_result_file.pf"
        call h%attr_string('/', 'status', 'running')
        call h%attr_string('/', 'status', 'complete')        ! replaced, not duplicated
        call h%series('/s', [3], 4)
        call h%append('/s', [1.0_wp, 2.0_wp, 3.0_wp])
        call h%close(.true., stat, msg)
#line 61 "/work/main/test/unit/test_result_file.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 61) )
  if (anyExceptions()) return
#line 62 "/work/main/test/unit/test_result_file.pf"
#line 62 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(exists(dir//'/new/a.h5'), 'final name after closing', &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 62) )
  if (anyExceptions()) return
#line 63 "/work/main/test/unit/test_result_file.pf"
#line 63 "/work/main/test/unit/test_result_file.pf"
  call assertFalse(exists(dir//'/new/a.h5.part'), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 63) )
  if (anyExceptions()) return
#line 64 "/work/main/test/unit/test_result_file.pf"
#line 64 "/work/main/test/unit/test_result_file.pf"
  call assertFalse(exists(dir//'/new/a.h5.lock'), 'lock released', &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 64) )
  if (anyExceptions()) return
#line 65 "/work/main/test/unit/test_result_file.pf"
        call h5_read_string_attr(dir//'/new/a.h5', '/', 'status', text, stat)
#line 66 "/work/main/test/unit/test_result_file.pf"
  call assertEqual(0, stat, &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 66) )
  if (anyExceptions()) return
#line 67 "/work/main/test/unit/test_result_file.pf"
#line 67 "/work/main/test/unit/test_result_file.pf"
  call assertEqual('complete', trim(text), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 67) )
  if (anyExceptions()) return
#line 68 "/work/main/test/unit/test_result_file.pf"
        call h5_dims(dir//'/new/a.h5', '/s', d, stat)
#line 69 "/work/main/test/unit/test_result_file.pf"
  call assertEqual([3, 1], d, &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 69) )
  if (anyExceptions()) return
#line 70 "/work/main/test/unit/test_result_file.pf"
        call h5_read_real(dir//'/new/a.h5', '/s', v, stat)
#line 71 "/work/main/test/unit/test_result_file.pf"
  call assertEqual([1.0_wp, 2.0_wp, 3.0_wp], v, &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 71) )
  if (anyExceptions()) return
#line 72 "/work/main/test/unit/test_result_file.pf"
        call remove_file(dir//'/new/a.h5', stat)
        call remove_directory(dir//'/new', stat)
        call remove_directory(dir, stat)
    end subroutine test_missing_directory_created_and_file_renamed_when_closed

    !@test
    subroutine test_second_writer_refused_while_the_first_holds_the_lock()
        type(h5_file_t) :: a, b
        integer :: stat
        character(len=msglen) :: msg
        call make_directories(dir, stat)
        call a%create(dir//'/b.h5', stat, msg)
#line 84 "/work/main/test/unit/test_result_file.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 84) )
  if (anyExceptions()) return
#line 85 "/work/main/test/unit/test_result_file.pf"
        call b%create(dir//'/b.h5', stat, msg)
#line 86 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(stat /= 0, 'second writer refused', &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 86) )
  if (anyExceptions()) return
#line 87 "/work/main/test/unit/test_result_file.pf"
#line 87 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(index(msg, 'another run is writing it') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 87) )
  if (anyExceptions()) return
#line 88 "/work/main/test/unit/test_result_file.pf"
#line 88 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(index(msg, dir//'/b.h5.lock') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 88) )
  if (anyExceptions()) return
#line 89 "/work/main/test/unit/test_result_file.pf"
#line 89 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(exists(dir//'/b.h5.part'), 'the first writer''s file untouched', &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 89) )
  if (anyExceptions()) return
#line 90 "/work/main/test/unit/test_result_file.pf"
        call a%close(.true., stat, msg)
#line 91 "/work/main/test/unit/test_result_file.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 91) )
  if (anyExceptions()) return
#line 92 "/work/main/test/unit/test_result_file.pf"
#line 92 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(exists(dir//'/b.h5'), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 92) )
  if (anyExceptions()) return
#line 93 "/work/main/test/unit/test_result_file.pf"
        call remove_file(dir//'/b.h5', stat)
        call remove_directory(dir, stat)
    end subroutine test_second_writer_refused_while_the_first_holds_the_lock

    !@test
    subroutine test_stale_lock_taken_over_and_older_result_removed()
        type(h5_file_t) :: h
        character(len=300) :: lockline
        integer :: stat
        character(len=msglen) :: msg
        call make_directories(dir, stat)
        call write_lines(dir//'/c.h5', [character(len=20) :: 'an older result'])
        ! a process id no system gives out
        lockline = '999999999 '//host_name()
        call write_lines(dir//'/c.h5.lock', [lockline])
        call h%create(dir//'/c.h5', stat, msg)
#line 109 "/work/main/test/unit/test_result_file.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 109) )
  if (anyExceptions()) return
#line 110 "/work/main/test/unit/test_result_file.pf"
#line 110 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(index(h%note, 'removed the stale lock') > 0, trim(h%note), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 110) )
  if (anyExceptions()) return
#line 111 "/work/main/test/unit/test_result_file.pf"
#line 111 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(index(h%note, 'removed the older result file '//dir//'/c.h5') > 0, trim(h%note), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 111) )
  if (anyExceptions()) return
#line 112 "/work/main/test/unit/test_result_file.pf"
#line 112 "/work/main/test/unit/test_result_file.pf"
  call assertFalse(exists(dir//'/c.h5'), 'the older result is gone while this run writes', &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 112) )
  if (anyExceptions()) return
#line 113 "/work/main/test/unit/test_result_file.pf"
        call h%close(.true., stat, msg)
#line 114 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(file_kind(dir//'/c.h5') == kind_regular, &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 114) )
  if (anyExceptions()) return
#line 115 "/work/main/test/unit/test_result_file.pf"
        call remove_file(dir//'/c.h5', stat)
        call remove_directory(dir, stat)
    end subroutine test_stale_lock_taken_over_and_older_result_removed

    !@test
    subroutine test_failing_hdf5_call_caught_and_partial_file_removed()
        type(h5_file_t) :: h
        logical :: named
        integer :: stat
        character(len=msglen) :: msg
        call make_directories(dir, stat)
        call h%create(dir//'/d.h5', stat, msg)
#line 127 "/work/main/test/unit/test_result_file.pf"
  call assertEqual(0, stat, trim(msg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 127) )
  if (anyExceptions()) return
#line 128 "/work/main/test/unit/test_result_file.pf"
        ! a write HDF5 refuses: its group does not exist
        call h%write_real('/no_such_group/x', [1.0_wp], [1])
#line 130 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(h%failed(), 'the failure is kept', &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 130) )
  if (anyExceptions()) return
#line 131 "/work/main/test/unit/test_result_file.pf"
        named = index(h%errmsg, 'writing '//dir//'/d.h5 failed (creating /no_such_group/x)') > 0
#line 132 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(named, trim(h%errmsg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 132) )
  if (anyExceptions()) return
#line 133 "/work/main/test/unit/test_result_file.pf"
#line 133 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(index(h%errmsg, 'H5D') > 0, 'HDF5''s failing call is named: '//trim(h%errmsg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 133) )
  if (anyExceptions()) return
#line 134 "/work/main/test/unit/test_result_file.pf"
        msg = h%errmsg
        call h%series('/later', [2])                 ! does nothing after a failure
        call h%append('/later', [1.0_wp, 2.0_wp])
#line 137 "/work/main/test/unit/test_result_file.pf"
  call assertEqual(trim(msg), trim(h%errmsg), 'the first failure is the one reported', &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 137) )
  if (anyExceptions()) return
#line 138 "/work/main/test/unit/test_result_file.pf"
        call h%close(.true., stat, msg)
#line 139 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(stat /= 0, &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 139) )
  if (anyExceptions()) return
#line 140 "/work/main/test/unit/test_result_file.pf"
#line 140 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(index(msg, 'the partial file '//dir//'/d.h5.part was removed') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 140) )
  if (anyExceptions()) return
#line 141 "/work/main/test/unit/test_result_file.pf"
#line 141 "/work/main/test/unit/test_result_file.pf"
  call assertFalse(exists(dir//'/d.h5.part'), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 141) )
  if (anyExceptions()) return
#line 142 "/work/main/test/unit/test_result_file.pf"
#line 142 "/work/main/test/unit/test_result_file.pf"
  call assertFalse(exists(dir//'/d.h5'), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 142) )
  if (anyExceptions()) return
#line 143 "/work/main/test/unit/test_result_file.pf"
#line 143 "/work/main/test/unit/test_result_file.pf"
  call assertFalse(exists(dir//'/d.h5.lock'), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 143) )
  if (anyExceptions()) return
#line 144 "/work/main/test/unit/test_result_file.pf"
        call remove_directory(dir, stat)
    end subroutine test_failing_hdf5_call_caught_and_partial_file_removed

    !@test
    subroutine test_directory_in_the_way_refused_in_one_line()
        type(h5_file_t) :: h
        integer :: stat
        character(len=msglen) :: msg
        call make_directories(dir//'/e.h5', stat)
        call h%create(dir//'/e.h5', stat, msg)
#line 154 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(stat /= 0, &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 154) )
  if (anyExceptions()) return
#line 155 "/work/main/test/unit/test_result_file.pf"
#line 155 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(index(msg, 'it is a directory') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 155) )
  if (anyExceptions()) return
#line 156 "/work/main/test/unit/test_result_file.pf"
#line 156 "/work/main/test/unit/test_result_file.pf"
  call assertFalse(exists(dir//'/e.h5.lock'), 'nothing left behind', &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 156) )
  if (anyExceptions()) return
#line 157 "/work/main/test/unit/test_result_file.pf"
        call write_lines(dir//'/f', [character(len=4) :: 'file'])
        call h%create(dir//'/f/g.h5', stat, msg)
#line 159 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(stat /= 0, &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 159) )
  if (anyExceptions()) return
#line 160 "/work/main/test/unit/test_result_file.pf"
#line 160 "/work/main/test/unit/test_result_file.pf"
  call assertTrue(index(msg, dir//'/f is a regular file, not a directory') > 0, trim(msg), &
 & location=SourceLocation( &
 & 'test_result_file.pf', &
 & 160) )
  if (anyExceptions()) return
#line 161 "/work/main/test/unit/test_result_file.pf"
        call delete_file(dir//'/f')
        call remove_directory(dir//'/e.h5', stat)
        call remove_directory(dir, stat)
    end subroutine test_directory_in_the_way_refused_in_one_line

end module test_result_file

module Wraptest_result_file
   use FUnit
   use test_result_file
   implicit none
   private

contains


end module Wraptest_result_file

function test_result_file_suite() result(suite)
   use FUnit
   use test_result_file
   use Wraptest_result_file
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_result_file_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_missing_directory_created_and_file_renamed_when_closed', &
      test_missing_directory_created_and_file_renamed_when_closed))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_second_writer_refused_while_the_first_holds_the_lock', &
      test_second_writer_refused_while_the_first_holds_the_lock))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_stale_lock_taken_over_and_older_result_removed', &
      test_stale_lock_taken_over_and_older_result_removed))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_failing_hdf5_call_caught_and_partial_file_removed', &
      test_failing_hdf5_call_caught_and_partial_file_removed))
   call suite%addTest(t)

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_directory_in_the_way_refused_in_one_line', &
      test_directory_in_the_way_refused_in_one_line))
   call suite%addTest(t)


end function test_result_file_suite

