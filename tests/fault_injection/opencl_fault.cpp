// A test-only OpenCL fault injector, LD_PRELOADed in front of the ICD loader: the Nth call of one
// OpenCL entry point fails with a chosen status, every other call is forwarded unchanged
// (dlsym(RTLD_NEXT)). The product has no hook for this; tests/test_opencl_faults.cpp drives it.
//   SSRCL_FAULT_CALL    clEnqueueNDRangeKernel, clEnqueueReadBuffer, clEnqueueWriteBuffer, clEnqueueMapBuffer
//                       or clCreateBuffer
//   SSRCL_FAULT_AT      which call of it fails, counting from 1 (default 1)
//   SSRCL_FAULT_STATUS  the status returned (default CL_OUT_OF_RESOURCES, -5)
// It announces the injected failure on stderr, so a test can tell it really happened.
#define CL_TARGET_OPENCL_VERSION 300
#include <CL/cl.h>
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace {

// Nonzero (the status to return) when this call of `name` is the one to fail.
cl_int injected(const char* name) {
  static int calls = 0;  // calls of the chosen entry point; one entry point is chosen per process
  const char* chosen = getenv("SSRCL_FAULT_CALL");
  if (!chosen || strcmp(chosen, name) != 0) return CL_SUCCESS;
  const char* at = getenv("SSRCL_FAULT_AT");
  const char* status = getenv("SSRCL_FAULT_STATUS");
  if (++calls != (at ? std::atoi(at) : 1)) return CL_SUCCESS;
  const cl_int code = status ? cl_int(std::atoi(status)) : CL_OUT_OF_RESOURCES;
  fprintf(stderr, "opencl_fault: %s call %d fails with %d\n", name, calls, int(code));
  return code;
}

// The loader's entry point of that name (the next definition after this library's).
void* next(const char* name) {
  void* f = dlsym(RTLD_NEXT, name);
  if (!f) {
    fprintf(stderr, "opencl_fault: no %s to forward to\n", name);
    abort();
  }
  return f;
}

}  // namespace

extern "C" {

CL_API_ENTRY cl_int CL_API_CALL clEnqueueNDRangeKernel(cl_command_queue q, cl_kernel k, cl_uint dim,
                                                       const size_t* offset, const size_t* global,
                                                       const size_t* local, cl_uint waits, const cl_event* wait,
                                                       cl_event* event) {
  const cl_int fault = injected("clEnqueueNDRangeKernel");
  if (fault) return fault;
  using Fn = cl_int (*)(cl_command_queue, cl_kernel, cl_uint, const size_t*, const size_t*, const size_t*, cl_uint,
                       const cl_event*, cl_event*);
  return reinterpret_cast<Fn>(next("clEnqueueNDRangeKernel"))(q, k, dim, offset, global, local, waits, wait, event);
}

CL_API_ENTRY cl_int CL_API_CALL clEnqueueReadBuffer(cl_command_queue q, cl_mem b, cl_bool blocking, size_t offset,
                                                    size_t size, void* ptr, cl_uint waits, const cl_event* wait,
                                                    cl_event* event) {
  const cl_int fault = injected("clEnqueueReadBuffer");
  if (fault) return fault;
  using Fn = cl_int (*)(cl_command_queue, cl_mem, cl_bool, size_t, size_t, void*, cl_uint, const cl_event*, cl_event*);
  return reinterpret_cast<Fn>(next("clEnqueueReadBuffer"))(q, b, blocking, offset, size, ptr, waits, wait, event);
}

CL_API_ENTRY cl_int CL_API_CALL clEnqueueWriteBuffer(cl_command_queue q, cl_mem b, cl_bool blocking, size_t offset,
                                                     size_t size, const void* ptr, cl_uint waits,
                                                     const cl_event* wait, cl_event* event) {
  const cl_int fault = injected("clEnqueueWriteBuffer");
  if (fault) return fault;
  using Fn = cl_int (*)(cl_command_queue, cl_mem, cl_bool, size_t, size_t, const void*, cl_uint, const cl_event*,
                       cl_event*);
  return reinterpret_cast<Fn>(next("clEnqueueWriteBuffer"))(q, b, blocking, offset, size, ptr, waits, wait, event);
}

CL_API_ENTRY void* CL_API_CALL clEnqueueMapBuffer(cl_command_queue q, cl_mem b, cl_bool blocking, cl_map_flags flags,
                                                  size_t offset, size_t size, cl_uint waits, const cl_event* wait,
                                                  cl_event* event, cl_int* status) {
  const cl_int fault = injected("clEnqueueMapBuffer");
  if (fault) {
    if (status) *status = fault;
    return nullptr;
  }
  using Fn = void* (*)(cl_command_queue, cl_mem, cl_bool, cl_map_flags, size_t, size_t, cl_uint, const cl_event*,
                       cl_event*, cl_int*);
  return reinterpret_cast<Fn>(next("clEnqueueMapBuffer"))(q, b, blocking, flags, offset, size, waits, wait, event,
                                                          status);
}

CL_API_ENTRY cl_mem CL_API_CALL clCreateBuffer(cl_context context, cl_mem_flags flags, size_t size, void* host,
                                               cl_int* status) {
  const cl_int fault = injected("clCreateBuffer");
  if (fault) {
    if (status) *status = fault;
    return nullptr;
  }
  using Fn = cl_mem (*)(cl_context, cl_mem_flags, size_t, void*, cl_int*);
  return reinterpret_cast<Fn>(next("clCreateBuffer"))(context, flags, size, host, status);
}

}  // extern "C"
