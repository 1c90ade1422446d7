#pragma once
/// \file robust_method.h
/// \brief Runs robust matching (estimators/robust_matching.h: M, M-D, LMS, MM) as a row of
///        pcl_ls3d_compare, on the same input and with the same timing and result row as the
///        LS3D and PCL methods: the LZD rule (Li et al.'s LHD), 6 parameters, from the identity.
#include <pcl_ls3d/estimators/robust_matching.h>
#include <pcl_ls3d/evaluation/registration_run.h>

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <string>

namespace pcl_ls3d {
namespace evaluation {

/// "ROBUST-M", "ROBUST-MD", "ROBUST-LMS", "ROBUST-MM" (and "ROBUST-LS", ...).
std::string
robustMethodName(RobustMethod method);

/// \brief Aligns source to target with robustMatching() and the library defaults of `method`
///        (LZD rule, rigid, LMS subsets from Li eq. 12, MM 500 FAST-LTS starts); never throws.
///        sigma0 of the row is the estimator's robust scale σ̂.
RegistrationRun
runRobust(RobustMethod method, const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& source,
          const pcl::PointCloud<pcl::PointXYZ>::ConstPtr& target);

}  // namespace evaluation
}  // namespace pcl_ls3d
