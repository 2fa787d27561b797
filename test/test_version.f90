!> One version string: the code's constant equals fpm.toml's `version`.
program test_version
    use hn_version, only: code_version
    use hn_testing, only: test_suite_t
    implicit none
    type(test_suite_t) :: suite
    character(len=200) :: line, found
    integer :: u, ios, q1, q2
    found = ''
    open (newunit=u, file='fpm.toml', status='old', action='read', iostat=ios)
    if (ios == 0) then
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
    end if
    call suite%check(trim(found) == code_version, 'fpm.toml version equals code_version', &
                     'fpm.toml "'//trim(found)//'", code "'//code_version//'"')
    call suite%finish()
end program test_version
