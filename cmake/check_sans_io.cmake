# cmake -DFILES=a.cpp,b.hpp -DHEADERS=openlcb/x.hpp,... -P check_sans_io.cmake
# Fails when one of FILES includes Boost, asio, a thread primitive or one of HEADERS: the files of
# a sans-I/O library (openlcb/CMakeLists.txt's core) must build with none of them.
if(NOT FILES)
    message(FATAL_ERROR "check_sans_io: no FILES given")
endif()
string(REPLACE "," ";" files "${FILES}")
string(REPLACE "," ";" headers "${HEADERS}")
set(patterns "#[ \t]*include[ \t]*[<\"]boost/" "#[ \t]*include[ \t]*[<\"][^>\"]*asio"
             "#[ \t]*include[ \t]*<thread>" "#[ \t]*include[ \t]*<mutex>"
             "#[ \t]*include[ \t]*<shared_mutex>" "#[ \t]*include[ \t]*<condition_variable>"
             "#[ \t]*include[ \t]*<future>" "#[ \t]*include[ \t]*<pthread\\.h>")
foreach(header ${headers})
    string(REPLACE "." "\\." escaped "${header}")
    list(APPEND patterns "#[ \t]*include[ \t]*\"${escaped}\"")
endforeach()
set(found "")
list(LENGTH files count)
foreach(file ${files})
    file(STRINGS "${file}" lines REGEX "#[ \t]*include")
    foreach(line ${lines})
        foreach(pattern ${patterns})
            if(line MATCHES "${pattern}")
                list(APPEND found "${file}: ${line}")
                break()
            endif()
        endforeach()
    endforeach()
endforeach()
if(found)
    list(JOIN found "\n  " text)
    message(FATAL_ERROR "the sans-I/O core includes what it must not:\n  ${text}")
endif()
message(STATUS "check_sans_io: ${count} files, no Boost, asio, thread or transport include")
