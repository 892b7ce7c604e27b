// The command's memory, on transparent huge pages where it pays (MADV_HUGEPAGE; the kernel's
// default policy, "madvise", uses them only where asked): page faults weigh on a large repair and
// on a depth frame's fill in a fresh process.
// - At start-up: freed blocks stay with the process (a command allocates and frees images and
//   meshes of the same sizes again and again; glibc would map each block of 128 KB or more on its
//   own, return it when freed and fault its pages in anew), and the heap's first 200 MB,
//   shared by every thread, are advised.
// - operator new advises the whole huge pages of a block of 4 MB or more, wherever it lies (a
//   mesh of millions of faces fills arrays of tens of megabytes once each). Freeing stays glibc's
//   operator delete (free).
// Not in the sanitizer build, whose allocator is its own.
#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <new>

namespace {

constexpr std::size_t kHugePage = std::size_t{2} << 20;
constexpr std::size_t kAdvisedSize = 2 * kHugePage;

// The whole huge pages inside [block, block + size).
void advise_huge_pages(void* block, std::size_t size) {
  const auto begin = reinterpret_cast<std::uintptr_t>(block);
  const std::uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t last = (begin + size) & ~(kHugePage - 1);
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
}

// The heap's first kHeapReserve bytes, taken from the system at start-up (virtual memory only),
// shared by every thread: the images and arrays of a command fault in 2 MB at a time rather than
// 4 KB.
constexpr std::size_t kHeapReserve = std::size_t{200} << 20;

const bool heap_on_huge_pages = [] {
  mallopt(M_MMAP_THRESHOLD, 256 << 20);  // every block from the heap, none mapped on its own
  mallopt(M_TRIM_THRESHOLD, 512 << 20);  // freed blocks stay with the process
  mallopt(M_ARENA_MAX, 1);               // worker threads' blocks from the same heap
  void* block = std::malloc(kHeapReserve);
  if (!block) return false;
  advise_huge_pages(block, static_cast<char*>(sbrk(0)) - static_cast<char*>(block));
  std::free(block);
  return true;
}();

}  // namespace

void* operator new(std::size_t size) {
  void* block = std::malloc(size == 0 ? 1 : size);
  if (!block) throw std::bad_alloc();
  if (size >= kAdvisedSize) advise_huge_pages(block, size);
  return block;
}
