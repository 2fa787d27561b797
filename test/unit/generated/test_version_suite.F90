!> One version string: the code's constant equals fpm.toml's `version`.
module test_version
    use funit
    use hn_version, only: code_version
    implicit none

contains

    !@test
    subroutine test_fpm_toml_version_equals_code_version()
        character(len=200) :: line, found
        integer :: u, ios, q1, q2
        found = ''
        open (newunit=u, file='fpm.toml', status='old', action='read', iostat=ios)
#line 15 "/work/main/test/unit/test_version.pf"
  call assertEqual(0, ios, 'fpm.toml readable from the project root', &
 & location=SourceLocation( &
 & 'test_version.pf', &
 & 15) )
  if (anyExceptions()) return
#line 16 "/work/main/test/unit/test_version.pf"
        do
            read (u, '(a)', iostat=ios) line
            if (ios /= 0) exit
            if (index(adjustl(line), 'version') == 1) then
                q1 = index(line, '"'); q2 = index(line, '"', back=.true.)
                if (q2 > q1) found = line(q1 + 1:q2 - 1)
                exit
            end if
        end do
        close (u)
#line 26 "/work/main/test/unit/test_version.pf"
  call assertEqual(code_version, trim(found), 'fpm.toml version = code_version', &
 & location=SourceLocation( &
 & 'test_version.pf', &
 & 26) )
  if (anyExceptions()) return
#line 27 "/work/main/test/unit/test_version.pf"
    end subroutine test_fpm_toml_version_equals_code_version

end module test_version

module Wraptest_version
   use FUnit
   use test_version
   implicit none
   private

contains


end module Wraptest_version

function test_version_suite() result(suite)
   use FUnit
   use test_version
   use Wraptest_version
   implicit none
   type (TestSuite) :: suite

   class (Test), allocatable :: t

   suite = TestSuite('test_version_suite')

   if(allocated(t)) deallocate(t)
   allocate(t, source=TestMethod('test_fpm_toml_version_equals_code_version', &
      test_fpm_toml_version_equals_code_version))
   call suite%addTest(t)


end function test_version_suite

