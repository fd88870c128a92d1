// Removed once the floquet sources land.
namespace ltp { int floquet_placeholder = 0; }
