// process_exchange(): Boost.MPI when built with it (SYMPL_WITH_MPI).
#include "output/mpi_exchange.hpp"

#include <cstdlib>
#include <memory>
#include <string>

#include <sympl/core/error.hpp>

#ifdef SYMPL_WITH_MPI
#include <boost/mpi/collectives.hpp>
#include <boost/mpi/communicator.hpp>
#include <boost/mpi/environment.hpp>
#include <boost/serialization/string.hpp>
#include <boost/serialization/vector.hpp>
#endif

namespace sympl::app {

namespace {
// The launcher's variable, if any: Open MPI's, PMIx's, or MPICH/Hydra's.
const char* launcher_variable() {
    for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
        if (std::getenv(v)) return v;
    return nullptr;
}
}  // namespace

bool built_with_mpi() {
#ifdef SYMPL_WITH_MPI
    return true;
#else
    return false;
#endif
}

exchange process_exchange() {
    const char* variable = launcher_variable();
    if (!variable) return {};
#ifdef SYMPL_WITH_MPI
    // One environment for the process's life: MPI_Finalize at exit.
    static std::unique_ptr<boost::mpi::environment> environment = std::make_unique<boost::mpi::environment>();
    static boost::mpi::communicator world;
    exchange x;
    x.rank = world.rank();
    x.size = world.size();
    x.gather = [](const std::string& mine) {
        std::vector<std::string> all;
        boost::mpi::gather(world, mine, all, 0);
        return all;
    };
    x.abort_all = [](int code) { world.abort(code); };
    return x;
#else
    throw invalid_argument(std::string("started by an MPI launcher (") + variable + " = " + std::getenv(variable) +
                           ") but this sympl was built without MPI; expected a build with Open MPI and Boost.MPI "
                           "(libopenmpi-dev, libboost-mpi-dev) or a run without mpirun");
#endif
}

}  // namespace sympl::app
