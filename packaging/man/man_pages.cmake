# The man pages, generated at build time by help2man from each program's --help (and its
# subcommands'), plus man/*.h2m for what --help does not say; compressed as Debian wants.
# check_man_pages.py (ctest) fails when an option of a --help is missing from the pages.
find_program(OLCB_HELP2MAN help2man)
if(NOT OLCB_HELP2MAN)
    message(STATUS "help2man not found: no man pages (ci/setup installs it)")
    return()
endif()
set(olcb_man_dir "${CMAKE_CURRENT_BINARY_DIR}/man")
set(olcb_help_of "${CMAKE_CURRENT_SOURCE_DIR}/man/help_of")
set(olcb_man_pages)
# olcb_man_page(PAGE TARGET WORD...): PAGE.1.gz from `TARGET WORD --help` for each WORD ("-":
# the program's own --help).
function(olcb_man_page page target)
    set(out "${olcb_man_dir}/${page}.1")
    set(include "${CMAKE_CURRENT_SOURCE_DIR}/man/${page}.h2m")
    list(JOIN ARGN " " words)  # one shell command line for help2man
    add_custom_command(OUTPUT "${out}.gz"
        COMMAND ${CMAKE_COMMAND} -E make_directory "${olcb_man_dir}"
        COMMAND ${OLCB_HELP2MAN} --no-info --no-discard-stderr --section=1
                "--include=${include}" "--output=${out}"
                "${olcb_help_of} ${page} $<TARGET_FILE:${target}> ${words}"
        COMMAND gzip -9nf "${out}"
        DEPENDS ${target} "${include}" "${olcb_help_of}"
        COMMENT "man page ${page}.1" VERBATIM)
    set(olcb_man_pages ${olcb_man_pages} "${out}.gz" PARENT_SCOPE)
endfunction()
olcb_man_page(simnode simnode -)
olcb_man_page(simnode-ctl simnode ctl)
olcb_man_page(lcc-conform lcc-conform -)
olcb_man_page(lcc-cdi lcc-cdi - validate layout render)
add_custom_target(olcb_man_pages ALL DEPENDS ${olcb_man_pages})
# ci/test builds the programs without the unit suites: the pages' test needs them too.
if(TARGET olcb_without_unit_tests)
    add_dependencies(olcb_without_unit_tests olcb_man_pages)
endif()
install(FILES ${olcb_man_pages} DESTINATION "${CMAKE_INSTALL_MANDIR}/man1")

# A program that gains an option its pages lack fails these (ctest -L packaging; "runner" too,
# so ci/test's run of the normal build includes them).
if(OLCB_TESTS)
    find_package(Python3 COMPONENTS Interpreter)
    if(Python3_Interpreter_FOUND)
        set(olcb_check "${CMAKE_CURRENT_SOURCE_DIR}/man/check_man_pages.py")
        add_test(NAME packaging.man_pages.simnode
                 COMMAND Python3::Interpreter ${olcb_check} $<TARGET_FILE:simnode>
                         "${olcb_man_dir}/simnode.1.gz" "${olcb_man_dir}/simnode-ctl.1.gz")
        add_test(NAME packaging.man_pages.lcc-conform
                 COMMAND Python3::Interpreter ${olcb_check} $<TARGET_FILE:lcc-conform>
                         "${olcb_man_dir}/lcc-conform.1.gz")
        add_test(NAME packaging.man_pages.lcc-cdi
                 COMMAND Python3::Interpreter ${olcb_check} $<TARGET_FILE:lcc-cdi>
                         "${olcb_man_dir}/lcc-cdi.1.gz")
        # The check itself: a page without --json must make it say so.
        add_test(NAME packaging.man_pages.missing_option_fails
                 COMMAND Python3::Interpreter ${olcb_check} $<TARGET_FILE:lcc-conform>
                         "${olcb_man_dir}/lcc-conform.1.gz" --without --json)
        set_tests_properties(packaging.man_pages.missing_option_fails PROPERTIES
                             PASS_REGULAR_EXPRESSION "lcc-conform: --json is in --help but not in")
        set_tests_properties(packaging.man_pages.simnode packaging.man_pages.lcc-conform
                             packaging.man_pages.lcc-cdi packaging.man_pages.missing_option_fails
                             PROPERTIES LABELS "runner;packaging")
    endif()
endif()
