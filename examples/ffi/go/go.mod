module leptrino.example/ffi

go 1.22
